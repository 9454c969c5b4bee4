use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn mutate<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    let mut s = x[0];
    s = s + m[0];
    s
}

fn main() {}
