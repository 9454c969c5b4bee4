use calib_macros::interval_model; trait Scalar: Sized { fn sqr(self) -> Self; }

fn helper<S: Scalar>(a: S) -> S {
    a.sqr()
}

#[interval_model]
fn calls<S: Scalar>(x: &[S; 1], m: &[S; 1]) -> S {
    helper(x[0]) - m[0]
}

fn main() {}
