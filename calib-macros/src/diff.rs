//! Symbolic reverse-mode differentiation on the graph.
//!
//! The adjoint of a node is the derivative of the output with respect to it; adjoints are built as
//! new graph nodes, so they share subexpressions with the value and with each other, and the final
//! gradient is `adjoint(Input(arg, i))`. Each rule is the chain rule for one operation:
//! `d(a*b) = b da + a db`, `d(a/b) = da/b - (a/b) db/b`, `d sqrt(a) = da / (2 sqrt(a))`, ...

use crate::graph::{Arg, Graph, Id, Node};

/// The gradient of node `out` with respect to the inputs of `arg`, `len` of them (the zero constant
/// where the output does not depend on an input).
pub struct Gradient {
    pub x: Vec<Id>,
    pub m: Vec<Id>,
}

/// Differentiates `out` with respect to every input.
pub fn gradient(g: &mut Graph, out: Id, nx: usize, nm: usize) -> Gradient {
    let mut adjoint: Vec<Option<Id>> = vec![None; out + 1];
    adjoint[out] = Some(g.exact(1.0));
    for id in (0..=out).rev() {
        let Some(adj) = adjoint[id] else { continue };
        for (operand, contribution) in local_adjoints(g, id, adj) {
            adjoint[operand] = Some(match adjoint[operand] {
                None => contribution,
                Some(prev) => g.add(prev, contribution),
            });
        }
    }
    let of_input = |g: &mut Graph, arg: Arg, i: usize| {
        let node = g.input(arg, i);
        adjoint
            .get(node)
            .copied()
            .flatten()
            .unwrap_or_else(|| g.zero())
    };
    Gradient {
        x: (0..nx).map(|i| of_input(g, Arg::X, i)).collect(),
        m: (0..nm).map(|i| of_input(g, Arg::M, i)).collect(),
    }
}

/// For node `n` with adjoint `adj`, the contributions `(operand, adj * d n / d operand)`.
fn local_adjoints(g: &mut Graph, n: Id, adj: Id) -> Vec<(Id, Id)> {
    match g.node(n) {
        Node::Input(..) | Node::Const(_) => vec![],
        Node::Add(a, b) => vec![(a, adj), (b, adj)],
        Node::Sub(a, b) => {
            let nb = g.neg(adj);
            vec![(a, adj), (b, nb)]
        }
        Node::Mul(a, b) => {
            let da = g.mul(adj, b);
            let db = g.mul(adj, a);
            vec![(a, da), (b, db)]
        }
        Node::Div(a, b) => {
            let da = g.div(adj, b);
            let t = g.mul(adj, n);
            let t = g.div(t, b);
            let db = g.neg(t);
            vec![(a, da), (b, db)]
        }
        Node::Neg(a) => {
            let da = g.neg(adj);
            vec![(a, da)]
        }
        Node::Sqr(a) => {
            let two = g.exact(2.0);
            let t = g.mul(two, a);
            vec![(a, g.mul(adj, t))]
        }
        Node::Powi(a, k) => {
            let kc = g.exact(f64::from(k));
            let p = g.powi(a, k - 1);
            let t = g.mul(kc, p);
            vec![(a, g.mul(adj, t))]
        }
        Node::Sqrt(a) => {
            let two = g.exact(2.0);
            let t = g.mul(two, n);
            vec![(a, g.div(adj, t))]
        }
        Node::Sin(a) => {
            let c = g.cos(a);
            vec![(a, g.mul(adj, c))]
        }
        Node::Cos(a) => {
            let s = g.sin(a);
            let t = g.mul(adj, s);
            vec![(a, g.neg(t))]
        }
        Node::Tan(a) => {
            let one = g.exact(1.0);
            let s = g.sqr(n);
            let t = g.add(one, s);
            vec![(a, g.mul(adj, t))]
        }
    }
}

/// Per input (the parameters, then the measurements), whether some derivative in `grads` depends
/// on it. An input on which no first derivative depends enters every output linearly: every
/// second and third derivative involving it is 0 (the kernel leaves it out of its second-order
/// bounds). Structural: a derivative that happens to cancel still counts as depending.
pub fn curved_inputs(g: &Graph, grads: &[Gradient], nx: usize, nm: usize) -> Vec<bool> {
    let n = nx + nm;
    let words = n.div_ceil(64).max(1);
    let mut depends = vec![0u64; g.len() * words];
    for id in 0..g.len() {
        match g.node(id) {
            Node::Input(arg, i) => {
                let k = if arg == Arg::X { i } else { nx + i };
                depends[id * words + k / 64] |= 1 << (k % 64);
            }
            node => {
                for operand in node.operands() {
                    for w in 0..words {
                        depends[id * words + w] |= depends[operand * words + w];
                    }
                }
            }
        }
    }
    let mut curved = vec![false; n];
    for d in grads.iter().flat_map(|gr| gr.x.iter().chain(&gr.m)) {
        for (k, c) in curved.iter_mut().enumerate() {
            *c |= depends[d * words + k / 64] & (1 << (k % 64)) != 0;
        }
    }
    curved
}
