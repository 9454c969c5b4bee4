use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

#[interval_model]
fn looping<S: Scalar>(x: &[S; 2], _m: &[S; 1]) -> S {
    let s = x[0];
    for _ in 0..2 {}
    s
}

fn main() {}
