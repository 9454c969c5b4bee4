//! Small dense linear algebra in caller-provided buffers (no allocation).

/// Inverts the `n x n` row-major matrix `a` (destroyed) into `inv` by Gauss–Jordan elimination with
/// partial pivoting; returns false if a pivot is zero or not finite.
pub(crate) fn gauss_jordan_inverse(n: usize, a: &mut [f64], inv: &mut [f64]) -> bool {
    inv.iter_mut().for_each(|v| *v = 0.0);
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    for col in 0..n {
        let (mut piv, mut best) = (col, a[col * n + col].abs());
        for r in col + 1..n {
            let v = a[r * n + col].abs();
            if v > best {
                piv = r;
                best = v;
            }
        }
        if best < 1e-300 || !best.is_finite() {
            return false;
        }
        if piv != col {
            for c in 0..n {
                a.swap(piv * n + c, col * n + c);
                inv.swap(piv * n + c, col * n + c);
            }
        }
        let d = 1.0 / a[col * n + col];
        for c in 0..n {
            a[col * n + c] *= d;
            inv[col * n + c] *= d;
        }
        for r in 0..n {
            if r != col {
                let f = a[r * n + col];
                if f != 0.0 {
                    for c in 0..n {
                        a[r * n + c] -= f * a[col * n + c];
                        inv[r * n + c] -= f * inv[col * n + c];
                    }
                }
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverts_and_detects_singularity() {
        let mut a = [0.0, 2.0, 1.0, 1.0];
        let mut inv = [0.0; 4];
        assert!(gauss_jordan_inverse(2, &mut a, &mut inv));
        assert_eq!(inv, [-0.5, 1.0, 0.5, 0.0]);
        let mut s = [1.0, 2.0, 2.0, 4.0];
        assert!(!gauss_jordan_inverse(2, &mut s, &mut inv));
    }
}
