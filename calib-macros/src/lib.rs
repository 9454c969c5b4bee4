//! # calib-macros
//!
//! The `#[interval_model]` attribute (use it through `calib_core::interval_model`).
//!
//! Applied to `fn name<S: Scalar>(x: &[S; NX], m: &[S; NM]) -> S`, it keeps the function and emits a
//! unit struct `Name` implementing `calib_core::Model<NX, NM>` with point, interval and Jacobian
//! evaluators, all straight-line code generated at compile time. Applied to a function returning
//! `[S; NR]` (several residuals of one configuration sharing its measurements, `NR >= 2`), the
//! struct implements `calib_core::VectorModel<NX, NM, NR>` instead (`[S; 1]` gives a `Model`).
//! `#[interval_model(curvature)]` (vector models) also implements `calib_core::Curvature`: the
//! values' evaluator over second-order jets of jets, the second and third derivatives the
//! kernel's second-order emptiness proofs need (compiled only where asked for: they make the
//! generated code several times larger). The stages, one file each:
//! `parse.rs` (signature), `lower.rs` (body to an expression graph, rejecting unsupported syntax with
//! spanned errors), `diff.rs` (symbolic reverse-mode differentiation on the graph, sharing common
//! subexpressions), `rewrite.rs` (enclosing the literals of the kept function) and `expand.rs`
//! (code generation). Literals are enclosed exactly by `literal.rs`.
#![deny(unsafe_code)]

mod diff;
mod expand;
mod graph;
mod literal;
mod lower;
mod parse;
mod rewrite;

use proc_macro::TokenStream;
use quote::quote;

/// Generates point, interval and Jacobian evaluators for a residual written over a generic scalar.
///
/// See the `calib_core` crate documentation for the supported body language and an example.
#[proc_macro_attribute]
pub fn interval_model(attr: TokenStream, item: TokenStream) -> TokenStream {
    let attr = proc_macro2::TokenStream::from(attr);
    let mut item = syn::parse_macro_input!(item as syn::ItemFn);
    let curvature = match attr.to_string().as_str() {
        "" => false,
        "curvature" => true,
        _ => {
            let err = syn::Error::new_spanned(
                attr,
                "#[interval_model] takes no arguments, or `curvature` (second and third \
                 derivatives for second-order emptiness proofs, vector models only)",
            );
            return error_with_stub(&item, err);
        }
    };
    let result = parse::signature(&item).and_then(|sig| {
        let (mut graph, outputs) = lower::lower(&sig, &item.block)?;
        let grads: Vec<_> = outputs
            .iter()
            .map(|&out| diff::gradient(&mut graph, out, sig.x.1, sig.m.1))
            .collect();
        if curvature && outputs.len() == 1 {
            return Err(syn::Error::new_spanned(
                &item.sig.output,
                "#[interval_model(curvature)] needs a vector model: return `[S; NR]`",
            ));
        }
        Ok((sig, graph, outputs, grads))
    });
    match result {
        Ok((sig, graph, outputs, grads)) => {
            let generated = expand::model(&item, &sig, &graph, &outputs, &grads, curvature);
            rewrite::enclose_literals(&mut item.block, &sig.scalar);
            quote!(#item #generated).into()
        }
        Err(err) => error_with_stub(&item, err),
    }
}

/// The error plus the function's signature (with a body that cannot fail to type-check) and a stub
/// struct, so that the user sees one clear error instead of a cascade.
fn error_with_stub(item: &syn::ItemFn, err: syn::Error) -> TokenStream {
    let error = err.to_compile_error();
    let stub = expand::stub(item);
    let mut item = item.clone();
    item.attrs
        .push(syn::parse_quote!(#[allow(unused_variables)]));
    item.block = syn::parse_quote!({ ::core::panic!("#[interval_model] rejected this function") });
    quote!(#error #item #stub).into()
}
