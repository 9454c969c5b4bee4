//! Proofs about parameter vectors and boxes: that a point or a box is consistent with the data
//! (sign tests, and the coupled existence test for vector models), that a box holds no consistent
//! vector where the linear relaxation cannot show it (second order), and the Chebyshev (minimax)
//! fits these proofs start from, which also give the smallest consistent error scale.

pub(crate) mod chebyshev;
pub(crate) mod consistency;
pub(crate) mod existence;
pub(crate) mod second_order;
pub(crate) mod segment;
pub(crate) mod witness;
