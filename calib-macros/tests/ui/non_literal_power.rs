use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn power<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    let n = 3;
    x[0].powi(n) - m[0]
}

fn main() {}
