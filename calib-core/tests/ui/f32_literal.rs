use calib_core::{interval_model, Scalar};

#[interval_model]
fn single<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    x[0] * 0.5f32 - m[0]
}

fn main() {}
