use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

const K: f64 = 2.0;

#[interval_model]
fn global<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    x[0] * K - m[0]
}

fn main() {}
