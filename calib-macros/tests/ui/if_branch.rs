use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn branchy<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    if true { x[0] } else { m[0] }
}

fn main() {}
