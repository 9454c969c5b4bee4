//! Rewriting the kept function so that its literals are enclosed too.
//!
//! The function stays as written, except that every literal in a value position (and every
//! `S::cst(literal)`) becomes `<S as Scalar>::enclose(nearest, lo, hi)`: the function then compiles
//! over a generic scalar with bare literals (`2.0 * q1`), and calling it with `S = Interval`
//! encloses the decimal values just like the generated evaluators. Exponents of `powi` and indices
//! stay integers.

use crate::literal;
use proc_macro2::TokenStream;
use quote::quote;
use syn::visit_mut::{self, VisitMut};
use syn::{Expr, Ident, Lit, UnOp};

/// Rewrites the literals of `block` in place.
pub fn enclose_literals(block: &mut syn::Block, scalar: &Ident) {
    LiteralRewriter { scalar }.visit_block_mut(block);
}

/// The tokens of `<S as Scalar>::enclose(..)` for a literal, or `None` if it is not a decimal.
pub fn enclosure_tokens(scalar: &Ident, lit: &Lit) -> Option<TokenStream> {
    let digits = match lit {
        Lit::Float(f) => f.base10_digits(),
        Lit::Int(i) => i.base10_digits(),
        _ => return None,
    };
    let e = literal::enclose(digits)?;
    Some(constant_tokens(scalar, e.nearest, e.lo, e.hi))
}

/// The tokens of `<S as Scalar>::enclose(nearest, lo, hi)` with exact bit patterns.
pub fn constant_tokens(scalar: &Ident, nearest: f64, lo: f64, hi: f64) -> TokenStream {
    let (n, l, h) = (nearest.to_bits(), lo.to_bits(), hi.to_bits());
    quote! {
        <#scalar as ::calib_core::Scalar>::enclose(
            ::core::primitive::f64::from_bits(#n),
            ::core::primitive::f64::from_bits(#l),
            ::core::primitive::f64::from_bits(#h),
        )
    }
}

struct LiteralRewriter<'a> {
    scalar: &'a Ident,
}

impl LiteralRewriter<'_> {
    fn replacement(&self, e: &Expr) -> Option<Expr> {
        let tokens = match e {
            Expr::Lit(l) => enclosure_tokens(self.scalar, &l.lit)?,
            Expr::Call(c) => {
                let Expr::Path(p) = &*c.func else { return None };
                if p.path.segments.last()?.ident != "cst" || c.args.len() != 1 {
                    return None;
                }
                match &c.args[0] {
                    Expr::Lit(l) => enclosure_tokens(self.scalar, &l.lit)?,
                    Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
                        Expr::Lit(l) => {
                            let t = enclosure_tokens(self.scalar, &l.lit)?;
                            quote!((-#t))
                        }
                        _ => return None,
                    },
                    _ => return None,
                }
            }
            _ => return None,
        };
        syn::parse2(tokens).ok()
    }
}

impl VisitMut for LiteralRewriter<'_> {
    fn visit_expr_mut(&mut self, e: &mut Expr) {
        match self.replacement(e) {
            Some(new) => *e = new,
            None => visit_mut::visit_expr_mut(self, e),
        }
    }

    fn visit_expr_method_call_mut(&mut self, mc: &mut syn::ExprMethodCall) {
        // `.powi(n)` keeps its integer exponent; only the receiver holds values.
        self.visit_expr_mut(&mut mc.receiver);
        if mc.method != "powi" {
            for a in mc.args.iter_mut() {
                self.visit_expr_mut(a);
            }
        }
    }

    fn visit_expr_index_mut(&mut self, ix: &mut syn::ExprIndex) {
        self.visit_expr_mut(&mut ix.expr);
    }
}
