use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn vector<S: Scalar>(x: Vec<S>, m: &[S; 1]) -> S {
    x[0] - m[0]
}

fn main() {}
