//! Lowering the function body to the expression graph, rejecting everything outside the supported
//! language with an error that points at the offending tokens.

use crate::graph::{Arg, Constant, Graph, Id};
use crate::literal;
use crate::parse::Signature;
use std::collections::HashMap;
use syn::{BinOp, Block, Error, Expr, Lit, Member, Pat, Stmt, UnOp};

/// The supported body language, quoted in every error.
pub const SUPPORTED: &str = "supported in an #[interval_model] body: `let` bindings (with array and \
tuple patterns), + - * /, unary -, parentheses, blocks, float and integer literals, `S::cst(literal)`, \
indexing with constant indices, `*x`, array and tuple expressions, and the methods .sqr() .sqrt() \
.powi(n) .sin() .cos() .tan()";

/// Largest accepted `|n|` in `powi(n)`.
const MAX_POWER: i32 = 1024;

/// A value during lowering: a scalar node or an aggregate of values.
#[derive(Clone)]
enum Value {
    Scalar(Id),
    Array(Vec<Value>),
    Tuple(Vec<Value>),
}

fn unsupported(tokens: &dyn quote::ToTokens, what: &str) -> Error {
    Error::new_spanned(tokens, format!("{what} is not supported\n{SUPPORTED}"))
}

/// The error for an expression the evaluators cannot contain, saying what it is (a macro call,
/// branching, a loop, a cast, a closure, an assignment, or another expression).
fn refusal(e: &Expr) -> Error {
    match e {
        Expr::Macro(m) => unsupported(m, "a macro call"),
        Expr::If(_) | Expr::Match(_) => unsupported(
            e,
            "branching (`if`/`match`; the evaluators are straight-line code)",
        ),
        Expr::Loop(_) | Expr::While(_) | Expr::ForLoop(_) => {
            unsupported(e, "a loop (unroll it with `let` bindings)")
        }
        Expr::Cast(_) => unsupported(e, "a cast"),
        Expr::Closure(_) => unsupported(e, "a closure"),
        Expr::Assign(_) => unsupported(e, "assignment"),
        _ => unsupported(e, "this expression"),
    }
}

/// Lowers the body; returns the graph and the output nodes (one for a scalar residual, `NR` for an
/// array of residuals).
pub fn lower(sig: &Signature, body: &Block) -> syn::Result<(Graph, Vec<Id>)> {
    let mut lowering = Lowering {
        graph: Graph::default(),
        env: HashMap::new(),
    };
    for (arg, (name, len)) in [(Arg::X, &sig.x), (Arg::M, &sig.m)] {
        let items = (0..*len)
            .map(|i| Value::Scalar(lowering.graph.input(arg, i)))
            .collect();
        lowering.env.insert(name.to_string(), Value::Array(items));
    }
    let out = lowering.block(body)?;
    let outputs = match (sig.rows, out) {
        (None, Value::Scalar(id)) => vec![id],
        (None, _) => {
            return Err(Error::new_spanned(
                body,
                "the body must evaluate to a scalar, not an array or a tuple",
            ))
        }
        (Some(n), Value::Array(items)) if items.len() == n => items
            .into_iter()
            .map(|v| match v {
                Value::Scalar(id) => Ok(id),
                _ => Err(Error::new_spanned(
                    body,
                    "every element of the returned array must be a scalar",
                )),
            })
            .collect::<syn::Result<_>>()?,
        (Some(n), _) => {
            return Err(Error::new_spanned(
                body,
                format!("the body must evaluate to an array of {n} scalars, as the signature says"),
            ))
        }
    };
    Ok((lowering.graph, outputs))
}

struct Lowering {
    graph: Graph,
    env: HashMap<String, Value>,
}

impl Lowering {
    fn block(&mut self, block: &Block) -> syn::Result<Value> {
        let saved = self.env.clone();
        let Some((last, init)) = block.stmts.split_last() else {
            return Err(Error::new_spanned(block, "an empty block has no value"));
        };
        for stmt in init {
            match stmt {
                Stmt::Local(local) => {
                    if let Some(else_) = &local.init.as_ref().and_then(|i| i.diverge.as_ref()) {
                        return Err(unsupported(&else_.1, "`let ... else`"));
                    }
                    let Some(init) = &local.init else {
                        return Err(unsupported(local, "a `let` without a value"));
                    };
                    let value = self.expr(&init.expr)?;
                    self.bind(&local.pat, value)?;
                }
                Stmt::Expr(e, _) => {
                    return Err(unsupported(e, "a statement other than `let`"));
                }
                Stmt::Item(item) => return Err(unsupported(item, "an item inside the body")),
                Stmt::Macro(m) => return Err(unsupported(m, "a macro call")),
            }
        }
        let value = match last {
            Stmt::Expr(e, None) => self.expr(e)?,
            other => {
                return Err(Error::new_spanned(
                    other,
                    "the body must end with an expression (its value), without a semicolon",
                ))
            }
        };
        self.env = saved;
        Ok(value)
    }

    fn bind(&mut self, pat: &Pat, value: Value) -> syn::Result<()> {
        match pat {
            Pat::Ident(p) => {
                if let Some(r) = &p.by_ref {
                    return Err(unsupported(r, "`ref` binding"));
                }
                if let Some(m) = &p.mutability {
                    return Err(unsupported(
                        m,
                        "`mut` binding (values cannot be reassigned)",
                    ));
                }
                if let Some((_, sub)) = &p.subpat {
                    return Err(unsupported(sub, "a `@` pattern"));
                }
                self.env.insert(p.ident.to_string(), value);
                Ok(())
            }
            Pat::Wild(_) => Ok(()),
            Pat::Type(t) => self.bind(&t.pat, value),
            Pat::Paren(p) => self.bind(&p.pat, value),
            Pat::Slice(s) => match value {
                Value::Array(items) => self.bind_all(pat, s.elems.iter(), items, "array"),
                _ => Err(Error::new_spanned(
                    pat,
                    "this array pattern binds a non-array value",
                )),
            },
            Pat::Tuple(t) => match value {
                Value::Tuple(items) => self.bind_all(pat, t.elems.iter(), items, "tuple"),
                _ => Err(Error::new_spanned(
                    pat,
                    "this tuple pattern binds a non-tuple value",
                )),
            },
            other => Err(unsupported(other, "this pattern")),
        }
    }

    fn bind_all<'a>(
        &mut self,
        pat: &Pat,
        pats: impl ExactSizeIterator<Item = &'a Pat>,
        items: Vec<Value>,
        kind: &str,
    ) -> syn::Result<()> {
        if pats.len() != items.len() {
            return Err(Error::new_spanned(
                pat,
                format!(
                    "this {kind} pattern has {} elements but the value has {}",
                    pats.len(),
                    items.len()
                ),
            ));
        }
        for (p, v) in pats.zip(items) {
            if let Pat::Rest(r) = p {
                return Err(unsupported(r, "a `..` rest pattern"));
            }
            self.bind(p, v)?;
        }
        Ok(())
    }

    fn scalar(&mut self, e: &Expr) -> syn::Result<Id> {
        match self.expr(e)? {
            Value::Scalar(id) => Ok(id),
            _ => Err(Error::new_spanned(
                e,
                "expected a scalar here, found an array or a tuple",
            )),
        }
    }

    /// The value of an expression: the supported syntax lowered onto the graph, anything else
    /// refused with a spanned error ([`refusal`]).
    fn expr(&mut self, e: &Expr) -> syn::Result<Value> {
        Ok(match e {
            Expr::Lit(l) => Value::Scalar(self.literal(&l.lit)?),
            Expr::Path(p) => self.path(p)?,
            Expr::Paren(p) => self.expr(&p.expr)?,
            Expr::Group(g) => self.expr(&g.expr)?,
            Expr::Block(b) if b.label.is_none() => self.block(&b.block)?,
            Expr::Unary(u) => self.unary(e, u)?,
            Expr::Binary(b) => self.binary(b)?,
            Expr::Index(ix) => self.index(ix)?,
            Expr::Field(f) => self.field(f)?,
            Expr::Array(a) => Value::Array(
                a.elems
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<syn::Result<_>>()?,
            ),
            Expr::Tuple(t) => Value::Tuple(
                t.elems
                    .iter()
                    .map(|e| self.expr(e))
                    .collect::<syn::Result<_>>()?,
            ),
            Expr::MethodCall(mc) => Value::Scalar(self.method_call(mc)?),
            Expr::Call(c) => Value::Scalar(self.constant_call(c)?),
            _ => return Err(refusal(e)),
        })
    }

    /// A local name: a parameter or a `let` binding.
    fn path(&self, p: &syn::ExprPath) -> syn::Result<Value> {
        let name = p.path.get_ident().filter(|_| p.qself.is_none());
        let Some(name) = name else {
            return Err(unsupported(p, "a path other than a local name"));
        };
        match self.env.get(&name.to_string()) {
            Some(v) => Ok(v.clone()),
            None => Err(Error::new_spanned(
                p,
                format!("`{name}` is not a parameter or a `let` binding of this body"),
            )),
        }
    }

    /// `-a` on a scalar, or `*a` on an array argument (`e` is the whole expression, for errors).
    fn unary(&mut self, e: &Expr, u: &syn::ExprUnary) -> syn::Result<Value> {
        match u.op {
            UnOp::Neg(_) => {
                let a = self.scalar(&u.expr)?;
                Ok(Value::Scalar(self.graph.neg(a)))
            }
            UnOp::Deref(_) => match self.expr(&u.expr)? {
                v @ Value::Array(_) => Ok(v),
                _ => Err(Error::new_spanned(
                    e,
                    "only the array arguments can be dereferenced",
                )),
            },
            _ => Err(unsupported(e, "this unary operator")),
        }
    }

    /// `a + b`, `a - b`, `a * b` or `a / b` on scalars.
    fn binary(&mut self, b: &syn::ExprBinary) -> syn::Result<Value> {
        let l = self.scalar(&b.left)?;
        let r = self.scalar(&b.right)?;
        let g = &mut self.graph;
        Ok(Value::Scalar(match b.op {
            BinOp::Add(_) => g.add(l, r),
            BinOp::Sub(_) => g.sub(l, r),
            BinOp::Mul(_) => g.mul(l, r),
            BinOp::Div(_) => g.div(l, r),
            _ => return Err(unsupported(&b.op, "this binary operator")),
        }))
    }

    /// `a[i]`: an element of an array, at a constant index within its length.
    fn index(&mut self, ix: &syn::ExprIndex) -> syn::Result<Value> {
        let Value::Array(items) = self.expr(&ix.expr)? else {
            return Err(Error::new_spanned(&ix.expr, "only arrays can be indexed"));
        };
        let i = constant_index(&ix.index)?;
        match items.get(i) {
            Some(v) => Ok(v.clone()),
            None => Err(Error::new_spanned(
                &ix.index,
                format!(
                    "index {i} is out of bounds for an array of length {}",
                    items.len()
                ),
            )),
        }
    }

    /// `t.0`, `t.1`, ...: a field of a tuple.
    fn field(&mut self, f: &syn::ExprField) -> syn::Result<Value> {
        let Member::Unnamed(idx) = &f.member else {
            return Err(unsupported(&f.member, "a named field"));
        };
        let Value::Tuple(items) = self.expr(&f.base)? else {
            return Err(Error::new_spanned(
                &f.base,
                "only tuples have fields `.0`, `.1`, ...",
            ));
        };
        match items.get(idx.index as usize) {
            Some(v) => Ok(v.clone()),
            None => Err(Error::new_spanned(&f.member, "no such tuple field")),
        }
    }

    fn literal(&mut self, lit: &Lit) -> syn::Result<Id> {
        let (digits, suffix) = match lit {
            Lit::Float(f) => (f.base10_digits(), f.suffix()),
            Lit::Int(i) => (i.base10_digits(), i.suffix()),
            other => return Err(unsupported(other, "this literal")),
        };
        if !matches!(suffix, "" | "f64") {
            return Err(Error::new_spanned(
                lit,
                format!(
                    "literal suffix `{suffix}` is not supported; write a plain or `f64` literal"
                ),
            ));
        }
        let Some(e) = literal::enclose(digits) else {
            return Err(Error::new_spanned(
                lit,
                "this literal is not a finite f64 value",
            ));
        };
        Ok(self.graph.constant(Constant::from_enclosure(e)))
    }

    fn method_call(&mut self, mc: &syn::ExprMethodCall) -> syn::Result<Id> {
        if let Some(t) = &mc.turbofish {
            return Err(unsupported(t, "a turbofish"));
        }
        let method = mc.method.to_string();
        let a = self.scalar(&mc.receiver)?;
        let g = &mut self.graph;
        let expect_args = |n: usize| -> syn::Result<()> {
            if mc.args.len() == n {
                Ok(())
            } else {
                Err(Error::new_spanned(
                    mc,
                    format!("`.{method}()` takes {n} argument(s)"),
                ))
            }
        };
        Ok(match method.as_str() {
            "sqr" | "sqrt" | "sin" | "cos" | "tan" => {
                expect_args(0)?;
                match method.as_str() {
                    "sqr" => g.sqr(a),
                    "sqrt" => g.sqrt(a),
                    "sin" => g.sin(a),
                    "cos" => g.cos(a),
                    _ => g.tan(a),
                }
            }
            "powi" => {
                expect_args(1)?;
                let n = integer_literal(&mc.args[0])?;
                if n.abs() > i64::from(MAX_POWER) {
                    return Err(Error::new_spanned(
                        &mc.args[0],
                        format!("`.powi(n)` needs |n| <= {MAX_POWER}"),
                    ));
                }
                g.powi(a, n as i32)
            }
            _ => {
                return Err(unsupported(
                    &mc.method,
                    &format!("the method `.{method}()`"),
                ))
            }
        })
    }

    /// `S::cst(literal)` (any path ending in `cst`), possibly with a negated literal.
    fn constant_call(&mut self, c: &syn::ExprCall) -> syn::Result<Id> {
        let is_cst = matches!(&*c.func, Expr::Path(p) if p.path.segments.last().is_some_and(|s| s.ident == "cst"));
        if !is_cst {
            return Err(unsupported(
                &c.func,
                "a function call (only `S::cst(literal)`; inline helpers with `let` bindings)",
            ));
        }
        let [arg] = c.args.iter().collect::<Vec<_>>()[..] else {
            return Err(Error::new_spanned(c, "`S::cst` takes one literal argument"));
        };
        let (negative, lit) = match without_groups(arg) {
            Expr::Lit(l) => (false, &l.lit),
            Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => match &*u.expr {
                Expr::Lit(l) => (true, &l.lit),
                _ => return Err(cst_argument(arg)),
            },
            _ => return Err(cst_argument(arg)),
        };
        let id = self.literal(lit)?;
        Ok(if negative { self.graph.neg(id) } else { id })
    }
}

fn cst_argument(arg: &Expr) -> Error {
    Error::new_spanned(
        arg,
        "the argument of `S::cst` must be a numeric literal, so that it can be enclosed exactly",
    )
}

/// `e` without the invisible groups `macro_rules!` puts around substituted fragments (so that a
/// literal passed through a declarative macro is still a literal).
pub fn without_groups(mut e: &Expr) -> &Expr {
    while let Expr::Group(g) = e {
        e = &g.expr;
    }
    e
}

fn integer_literal(e: &Expr) -> syn::Result<i64> {
    match without_groups(e) {
        Expr::Lit(syn::ExprLit {
            lit: Lit::Int(i), ..
        }) => i.base10_parse::<i64>(),
        Expr::Unary(u) if matches!(u.op, UnOp::Neg(_)) => Ok(-integer_literal(&u.expr)?),
        Expr::Paren(p) => integer_literal(&p.expr),
        other => Err(Error::new_spanned(
            other,
            "expected an integer literal (a constant exponent)",
        )),
    }
}

fn constant_index(e: &Expr) -> syn::Result<usize> {
    match without_groups(e) {
        Expr::Lit(syn::ExprLit {
            lit: Lit::Int(i), ..
        }) => i.base10_parse::<usize>(),
        other => Err(Error::new_spanned(
            other,
            format!("the index must be an integer literal\n{SUPPORTED}"),
        )),
    }
}
