use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn indexed<S: Scalar>(x: &[S; 2], m: &[S; 1]) -> S {
    let i = 1;
    x[i] - m[0]
}

fn main() {}
