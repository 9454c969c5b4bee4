use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn expo<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    x[0].exp() - m[0]
}

fn main() {}
