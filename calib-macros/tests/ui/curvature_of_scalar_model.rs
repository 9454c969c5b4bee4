use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model(curvature)]
fn residual<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> S {
    x[0] - m[0]
}

fn main() {}
