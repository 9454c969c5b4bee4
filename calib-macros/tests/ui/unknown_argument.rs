use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model(hessian)]
fn rows<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> [S; 2] {
    [x[0] - m[0], x[1] - m[0]]
}

fn main() {}
