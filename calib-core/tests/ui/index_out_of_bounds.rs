use calib_core::{interval_model, Scalar};

#[interval_model]
fn outside<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> S {
    x[2] - m[0]
}

fn main() {}
