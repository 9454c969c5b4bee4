//! The intermediate representation: a hash-consed expression graph.
//!
//! Nodes are created bottom-up, so a node's id is larger than its operands' ids and id order is a
//! topological order. Identical nodes are created once (common subexpressions are shared), and a
//! few algebraic identities that are exact over the reals are applied on construction
//! (`a + 0 = a`, `a * 1 = a`, `a * 0 = 0`, `a * a = sqr(a)`, `-(-a) = a`, ...).

use crate::literal::Enclosure;
use std::collections::HashMap;

/// Index of a node in a [`Graph`].
pub type Id = usize;

/// Which argument array an input comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Arg {
    /// The parameters `x`.
    X,
    /// The measurements `M`.
    M,
}

/// A constant: the double nearest to it and an enclosing interval, stored as bit patterns so that
/// nodes can be hashed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Constant {
    pub nearest: u64,
    pub lo: u64,
    pub hi: u64,
}

impl Constant {
    pub fn exact(v: f64) -> Constant {
        Constant {
            nearest: v.to_bits(),
            lo: v.to_bits(),
            hi: v.to_bits(),
        }
    }

    pub fn from_enclosure(e: Enclosure) -> Constant {
        Constant {
            nearest: e.nearest.to_bits(),
            lo: e.lo.to_bits(),
            hi: e.hi.to_bits(),
        }
    }

    fn is_exactly(self, v: f64) -> bool {
        self.lo == self.hi && f64::from_bits(self.lo) == v
    }
}

/// One operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    Input(Arg, usize),
    Const(Constant),
    Add(Id, Id),
    Sub(Id, Id),
    Mul(Id, Id),
    Div(Id, Id),
    Neg(Id),
    Sqr(Id),
    Powi(Id, i32),
    Sqrt(Id),
    Sin(Id),
    Cos(Id),
    Tan(Id),
}

impl Node {
    /// The operands, in order.
    pub fn operands(self) -> Vec<Id> {
        match self {
            Node::Input(..) | Node::Const(_) => vec![],
            Node::Add(a, b) | Node::Sub(a, b) | Node::Mul(a, b) | Node::Div(a, b) => vec![a, b],
            Node::Neg(a)
            | Node::Sqr(a)
            | Node::Powi(a, _)
            | Node::Sqrt(a)
            | Node::Sin(a)
            | Node::Cos(a)
            | Node::Tan(a) => vec![a],
        }
    }
}

/// The expression graph.
#[derive(Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
}

impl Graph {
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id]
    }

    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = self.nodes.len();
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    fn is_const(&self, id: Id, v: f64) -> bool {
        matches!(self.nodes[id], Node::Const(c) if c.is_exactly(v))
    }

    pub fn input(&mut self, arg: Arg, i: usize) -> Id {
        self.intern(Node::Input(arg, i))
    }

    pub fn constant(&mut self, c: Constant) -> Id {
        self.intern(Node::Const(c))
    }

    pub fn exact(&mut self, v: f64) -> Id {
        self.constant(Constant::exact(v))
    }

    pub fn zero(&mut self) -> Id {
        self.exact(0.0)
    }

    pub fn add(&mut self, a: Id, b: Id) -> Id {
        if self.is_const(a, 0.0) {
            return b;
        }
        if self.is_const(b, 0.0) {
            return a;
        }
        if let Node::Neg(c) = self.nodes[b] {
            return self.sub(a, c);
        }
        if let Node::Neg(c) = self.nodes[a] {
            return self.sub(b, c);
        }
        self.intern(Node::Add(a.min(b), a.max(b)))
    }

    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        if a == b {
            return self.zero();
        }
        if self.is_const(b, 0.0) {
            return a;
        }
        if self.is_const(a, 0.0) {
            return self.neg(b);
        }
        if let Node::Neg(c) = self.nodes[b] {
            return self.add(a, c);
        }
        self.intern(Node::Sub(a, b))
    }

    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        if self.is_const(a, 0.0) || self.is_const(b, 0.0) {
            return self.zero();
        }
        if self.is_const(a, 1.0) {
            return b;
        }
        if self.is_const(b, 1.0) {
            return a;
        }
        if a == b {
            return self.sqr(a);
        }
        if let Node::Neg(c) = self.nodes[a] {
            let p = self.mul(c, b);
            return self.neg(p);
        }
        if let Node::Neg(c) = self.nodes[b] {
            let p = self.mul(a, c);
            return self.neg(p);
        }
        self.intern(Node::Mul(a.min(b), a.max(b)))
    }

    pub fn div(&mut self, a: Id, b: Id) -> Id {
        if self.is_const(b, 1.0) {
            return a;
        }
        if let Node::Neg(c) = self.nodes[a] {
            let q = self.div(c, b);
            return self.neg(q);
        }
        self.intern(Node::Div(a, b))
    }

    pub fn neg(&mut self, a: Id) -> Id {
        match self.nodes[a] {
            Node::Neg(c) => c,
            _ if self.is_const(a, 0.0) => a,
            _ => self.intern(Node::Neg(a)),
        }
    }

    pub fn sqr(&mut self, a: Id) -> Id {
        match self.nodes[a] {
            Node::Neg(c) => self.sqr(c),
            _ => self.intern(Node::Sqr(a)),
        }
    }

    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        match n {
            0 => self.exact(1.0),
            1 => a,
            2 => self.sqr(a),
            _ => self.intern(Node::Powi(a, n)),
        }
    }

    pub fn sqrt(&mut self, a: Id) -> Id {
        self.intern(Node::Sqrt(a))
    }

    pub fn sin(&mut self, a: Id) -> Id {
        self.intern(Node::Sin(a))
    }

    pub fn cos(&mut self, a: Id) -> Id {
        self.intern(Node::Cos(a))
    }

    pub fn tan(&mut self, a: Id) -> Id {
        self.intern(Node::Tan(a))
    }
}
