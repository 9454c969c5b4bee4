use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn runtime_constant<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    let c = 0.5f64;
    x[0] * S::cst(c + 1.0) - m[0]
}

fn main() {}
