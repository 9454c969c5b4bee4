use calib_core::{interval_model, Scalar};

#[interval_model]
fn power<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    let n = 3;
    x[0].powi(n) - m[0]
}

fn main() {}
