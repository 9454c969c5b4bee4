use calib_core::{interval_model, Scalar};

#[interval_model]
fn expo<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    x[0].exp() - m[0]
}

fn main() {}
