use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn array<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> S {
    let _ = m;
    *x
}

fn main() {}
