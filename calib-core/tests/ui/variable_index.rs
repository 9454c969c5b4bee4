use calib_core::{interval_model, Scalar};

#[interval_model]
fn indexed<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> S {
    let i = 1;
    x[i] - m[0]
}

fn main() {}
