//! Parsing and checking the signature `fn name<S: Scalar>(x: &[S; NX], m: &[S; NM]) -> S` (or
//! `-> [S; NR]`).

use proc_macro2::Span;
use syn::spanned::Spanned;
use syn::{Error, FnArg, GenericParam, Ident, ItemFn, Pat, ReturnType, Type};

/// What the code generator needs from the signature.
pub struct Signature {
    /// The scalar type parameter (`S`).
    pub scalar: Ident,
    /// Name and length of the parameter array `x`.
    pub x: (Ident, usize),
    /// Name and length of the measurement array `M`.
    pub m: (Ident, usize),
    /// `None` for a scalar residual (`-> S`), `Some(NR)` for `-> [S; NR]`.
    pub rows: Option<usize>,
}

const EXPECTED: &str =
    "#[interval_model] expects `fn name<S: Scalar>(x: &[S; NX], m: &[S; NM]) -> S` \
     (or `-> [S; NR]` for NR residuals sharing the measurements) with integer literals NX, NM, NR";

fn err(span: Span, what: &str) -> Error {
    Error::new(span, format!("{what}; {EXPECTED}"))
}

/// Checks the signature and extracts its parts.
pub fn signature(item: &ItemFn) -> syn::Result<Signature> {
    let sig = &item.sig;
    if let Some(t) = sig.constness.as_ref() {
        return Err(err(t.span(), "`const fn` is not supported"));
    }
    if let Some(t) = sig.asyncness.as_ref() {
        return Err(err(t.span(), "`async fn` is not supported"));
    }
    if let Some(t) = sig.unsafety.as_ref() {
        return Err(err(t.span(), "`unsafe fn` is not supported"));
    }
    if let Some(v) = sig.variadic.as_ref() {
        return Err(err(v.span(), "variadic arguments are not supported"));
    }
    let mut scalar = None;
    for p in &sig.generics.params {
        match p {
            GenericParam::Type(t) if scalar.is_none() => scalar = Some(t.ident.clone()),
            other => {
                return Err(err(
                    other.span(),
                    "only one generic parameter, the scalar type, is allowed",
                ))
            }
        }
    }
    let scalar = scalar.ok_or_else(|| {
        err(
            sig.ident.span(),
            "the function needs a scalar type parameter",
        )
    })?;
    if sig.inputs.len() != 2 {
        return Err(err(sig.inputs.span(), "expected exactly two arguments"));
    }
    let x = array_arg(&sig.inputs[0], &scalar)?;
    let m = array_arg(&sig.inputs[1], &scalar)?;
    let rows = match &sig.output {
        ReturnType::Type(_, ty) if is_scalar(ty, &scalar) => None,
        ReturnType::Type(_, ty) => match &**ty {
            Type::Array(a) if is_scalar(&a.elem, &scalar) => Some(literal_length(&a.len)?),
            _ => return Err(bad_return(ty.span())),
        },
        other => return Err(bad_return(other.span())),
    };
    Ok(Signature { scalar, x, m, rows })
}

fn bad_return(span: Span) -> Error {
    err(
        span,
        "the function must return the scalar type parameter or an array `[S; NR]` of it",
    )
}

/// A positive integer literal array length.
fn literal_length(len: &syn::Expr) -> syn::Result<usize> {
    let len = crate::lower::without_groups(len);
    let syn::Expr::Lit(syn::ExprLit {
        lit: syn::Lit::Int(n),
        ..
    }) = len
    else {
        return Err(err(
            len.span(),
            "the array length must be an integer literal",
        ));
    };
    let n = n.base10_parse::<usize>()?;
    if n == 0 {
        return Err(err(len.span(), "the array length must be positive"));
    }
    Ok(n)
}

fn is_scalar(ty: &Type, scalar: &Ident) -> bool {
    matches!(ty, Type::Path(p) if p.qself.is_none() && p.path.is_ident(scalar))
}

/// `name: &[S; N]` with a literal `N`.
fn array_arg(arg: &FnArg, scalar: &Ident) -> syn::Result<(Ident, usize)> {
    let FnArg::Typed(pt) = arg else {
        return Err(err(arg.span(), "`self` is not supported"));
    };
    let Pat::Ident(name) = &*pt.pat else {
        return Err(err(pt.pat.span(), "the argument must be a plain name"));
    };
    let bad = || err(pt.ty.span(), "the argument type must be `&[S; N]`");
    let Type::Reference(r) = &*pt.ty else {
        return Err(bad());
    };
    if r.mutability.is_some() {
        return Err(bad());
    }
    let Type::Array(a) = &*r.elem else {
        return Err(bad());
    };
    if !is_scalar(&a.elem, scalar) {
        return Err(bad());
    }
    Ok((name.ident.clone(), literal_length(&a.len)?))
}
