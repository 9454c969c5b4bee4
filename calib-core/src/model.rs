//! The [`Model`] trait: a residual `f(x, M)` with its point, interval and Jacobian evaluators.

use crate::Interval;

/// Value and both Jacobians of a residual at one point or over one box, computed together so that
/// shared subexpressions are evaluated once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Evaluation<S, const NX: usize, const NM: usize> {
    /// `f(x, M)`.
    pub value: S,
    /// `df/dx`.
    pub dx: [S; NX],
    /// `df/dM`.
    pub dm: [S; NM],
}

/// A scalar residual `f(x, M)` of `NX` unknown parameters `x` and `NM` measured quantities `M`
/// (paper eq. 4: the calibration equations are `f(x, M_k) = 0` for every measurement `k`).
///
/// `#[interval_model]` implements it for a unit struct generated from a generic function; a model with
/// runtime data can implement it by hand. The interval methods must enclose: for every `x` in the box
/// `x` and `M` in the box `m`, the point value (and each Jacobian entry) lies in the interval result.
pub trait Model<const NX: usize, const NM: usize> {
    /// `f(x, M)` in floating point.
    fn residual(&self, x: &[f64; NX], m: &[f64; NM]) -> f64;

    /// An enclosure of `{f(x, M) : x in x, M in m}`.
    fn residual_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> Interval;

    /// `df/dx (x, M)` in floating point.
    fn jacobian_x(&self, x: &[f64; NX], m: &[f64; NM]) -> [f64; NX];

    /// `df/dM (x, M)` in floating point.
    fn jacobian_m(&self, x: &[f64; NX], m: &[f64; NM]) -> [f64; NM];

    /// An enclosure of `{df/dx (x, M)}` over the boxes (the matrix rows `A` of paper eq. 6).
    fn jacobian_x_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [Interval; NX];

    /// An enclosure of `{df/dM (x, M)}` over the boxes (the matrix rows `B` of paper eq. 6).
    fn jacobian_m_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [Interval; NM];

    /// Value and both Jacobians in floating point, sharing common subexpressions.
    fn evaluate(&self, x: &[f64; NX], m: &[f64; NM]) -> Evaluation<f64, NX, NM> {
        Evaluation {
            value: self.residual(x, m),
            dx: self.jacobian_x(x, m),
            dm: self.jacobian_m(x, m),
        }
    }

    /// Enclosures of value and both Jacobians over the boxes, sharing common subexpressions.
    fn evaluate_interval(
        &self,
        x: &[Interval; NX],
        m: &[Interval; NM],
    ) -> Evaluation<Interval, NX, NM> {
        Evaluation {
            value: self.residual_interval(x, m),
            dx: self.jacobian_x_interval(x, m),
            dm: self.jacobian_m_interval(x, m),
        }
    }
}

impl<T: Model<NX, NM> + ?Sized, const NX: usize, const NM: usize> Model<NX, NM> for &T {
    fn residual(&self, x: &[f64; NX], m: &[f64; NM]) -> f64 {
        (**self).residual(x, m)
    }
    fn residual_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> Interval {
        (**self).residual_interval(x, m)
    }
    fn jacobian_x(&self, x: &[f64; NX], m: &[f64; NM]) -> [f64; NX] {
        (**self).jacobian_x(x, m)
    }
    fn jacobian_m(&self, x: &[f64; NX], m: &[f64; NM]) -> [f64; NM] {
        (**self).jacobian_m(x, m)
    }
    fn jacobian_x_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [Interval; NX] {
        (**self).jacobian_x_interval(x, m)
    }
    fn jacobian_m_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [Interval; NM] {
        (**self).jacobian_m_interval(x, m)
    }
    fn evaluate(&self, x: &[f64; NX], m: &[f64; NM]) -> Evaluation<f64, NX, NM> {
        (**self).evaluate(x, m)
    }
    fn evaluate_interval(
        &self,
        x: &[Interval; NX],
        m: &[Interval; NM],
    ) -> Evaluation<Interval, NX, NM> {
        (**self).evaluate_interval(x, m)
    }
}

/// `NR` residuals `f(x, M) = 0` of one configuration that share its measured quantities `M`: the
/// x, y and z of a tracked point, the `u, v` of an image point, a pose. The solution set is
/// `{x : for every configuration k there is ONE M in M_k with f(x, M) = 0 in all NR components}`
/// — a point that fits one row with one reading and another row with another reading of the same
/// configuration is not a solution (see [`crate::certificate`] for how the kernel proves it).
///
/// `#[interval_model]` implements it for a function returning `[S; NR]`; every scalar [`Model`]
/// is a `VectorModel<NX, NM, 1>`, so every kernel entry point takes both. The interval methods must
/// enclose, row by row, as for [`Model`].
pub trait VectorModel<const NX: usize, const NM: usize, const NR: usize> {
    /// `f(x, M)` in floating point, one entry per row.
    fn residuals(&self, x: &[f64; NX], m: &[f64; NM]) -> [f64; NR];

    /// Row by row, an enclosure of `{f_r(x, M) : x in x, M in m}`.
    fn residuals_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [Interval; NR];

    /// Value and both Jacobians of every row in floating point.
    fn evaluate_rows(&self, x: &[f64; NX], m: &[f64; NM]) -> [Evaluation<f64, NX, NM>; NR];

    /// Enclosures of value and both Jacobians of every row over the boxes.
    fn evaluate_rows_interval(
        &self,
        x: &[Interval; NX],
        m: &[Interval; NM],
    ) -> [Evaluation<Interval, NX, NM>; NR];

    /// `∂f_r/∂M (x, M)` of every row in floating point.
    fn jacobians_m(&self, x: &[f64; NX], m: &[f64; NM]) -> [[f64; NM]; NR] {
        self.evaluate_rows(x, m).map(|e| e.dm)
    }

    /// `f(x, M)` and `∂f/∂M (x, M)` of every row in floating point (what the search for a reading
    /// that fits a configuration needs; `#[interval_model]` skips the parameter derivatives).
    fn residuals_and_jacobians_m(
        &self,
        x: &[f64; NX],
        m: &[f64; NM],
    ) -> ([f64; NR], [[f64; NM]; NR]) {
        let e = self.evaluate_rows(x, m);
        (e.map(|r| r.value), e.map(|r| r.dm))
    }

    /// Row by row, an enclosure of `∂f_r/∂M` over the boxes (what the existence test of
    /// [`crate::certificate`] needs; `#[interval_model]` skips the parameter derivatives).
    fn jacobians_m_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [[Interval; NM]; NR] {
        self.evaluate_rows_interval(x, m).map(|e| e.dm)
    }

    /// Linear enclosures of every row over the boxes (see [`LinearEnclosure`]), when the model can
    /// compute them (`#[interval_model]` vector models do, in affine arithmetic); `None` by
    /// default. The Newton step adds their rows to the polyhedron.
    fn linear_enclosures(
        &self,
        _x: &[Interval; NX],
        _m: &[Interval; NM],
    ) -> Option<[LinearEnclosure<NX, NM>; NR]> {
        None
    }

    /// The rows' second and third derivatives, when the model provides them
    /// (`#[interval_model(curvature)]`); `None` by default. With them, the kernel tries a
    /// second-order emptiness proof ([`crate::second_order`]) where the contraction leaves a box
    /// undecided and no consistent point is found.
    fn curvature(&self) -> Option<&dyn crate::Curvature<NX, NM, NR>> {
        None
    }
}

/// A linear enclosure of a residual over a box `x` and a measurement box `m`: with
/// `x_j = mid(x_j) + rad(x_j) ε_j` and `M_i = mid(M_i) + rad(M_i) η_i`, for every `ε, η` in
/// `[-1, 1]`, `f(x, M) ∈ c + Σ_j gx_j ε_j + Σ_i gm_i η_i + [-e, e]` (the affine form of the
/// residual, [`crate::affine`]). Unlike the mean-value form, its slack `e` holds only the nonlinear
/// remainders and roundings, not the width of the Jacobian times the width of the box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinearEnclosure<const NX: usize, const NM: usize> {
    /// The centre.
    pub c: f64,
    /// Coefficients of the parameter noise symbols.
    pub gx: [f64; NX],
    /// Coefficients of the measurement noise symbols.
    pub gm: [f64; NM],
    /// The error radius (`>= 0`).
    pub e: f64,
}

impl<const NX: usize, const NM: usize> LinearEnclosure<NX, NM> {
    /// The range of the form over the boxes: `c ± (Σ|gx_j| + Σ|gm_i| + e)`, rounded outward.
    pub fn range(&self) -> Interval {
        use crate::interval::round::add_up;
        let r = self
            .gx
            .iter()
            .chain(&self.gm)
            .fold(self.e, |acc, g| add_up(acc, g.abs()));
        Interval::point(self.c) + Interval::new(-r, r)
    }
}

impl<T: Model<NX, NM> + ?Sized, const NX: usize, const NM: usize> VectorModel<NX, NM, 1> for T {
    #[inline]
    fn residuals(&self, x: &[f64; NX], m: &[f64; NM]) -> [f64; 1] {
        [self.residual(x, m)]
    }
    #[inline]
    fn residuals_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [Interval; 1] {
        [self.residual_interval(x, m)]
    }
    #[inline]
    fn evaluate_rows(&self, x: &[f64; NX], m: &[f64; NM]) -> [Evaluation<f64, NX, NM>; 1] {
        [self.evaluate(x, m)]
    }
    #[inline]
    fn evaluate_rows_interval(
        &self,
        x: &[Interval; NX],
        m: &[Interval; NM],
    ) -> [Evaluation<Interval, NX, NM>; 1] {
        [self.evaluate_interval(x, m)]
    }
    #[inline]
    fn jacobians_m(&self, x: &[f64; NX], m: &[f64; NM]) -> [[f64; NM]; 1] {
        [self.jacobian_m(x, m)]
    }
    #[inline]
    fn jacobians_m_interval(&self, x: &[Interval; NX], m: &[Interval; NM]) -> [[Interval; NM]; 1] {
        [self.jacobian_m_interval(x, m)]
    }
}
