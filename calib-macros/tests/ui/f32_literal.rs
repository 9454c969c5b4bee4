use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn single<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    x[0] * 0.5f32 - m[0]
}

fn main() {}
