use calib_core::{interval_model, Scalar};

#[interval_model]
fn vector<S: Scalar>(x: Vec<S>, m: &[S; 1]) -> S {
    x[0] - m[0]
}

fn main() {}
