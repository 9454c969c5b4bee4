use calib_core::{interval_model, Scalar};

#[interval_model]
fn runtime_constant<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    let c = 0.5f64;
    x[0] * S::cst(c + 1.0) - m[0]
}

fn main() {}
