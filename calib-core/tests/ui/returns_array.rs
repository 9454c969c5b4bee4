use calib_core::{interval_model, Scalar};

#[interval_model]
fn array<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> S {
    let _ = m;
    *x
}

fn main() {}
