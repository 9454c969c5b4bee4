use calib_core::{interval_model, Scalar};

#[interval_model]
fn rows<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> [S; 3] {
    [x[0] - m[0], x[1] - m[0]]
}

fn main() {}
