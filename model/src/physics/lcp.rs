//! Lemke's complementary pivoting method for the linear complementarity problem
//!
//! ```text
//! find z >= 0 with w = M z + q >= 0 and w . z = 0.
//! ```
//!
//! Dense tableau of the non-basic variables, covering vector of ones. The answer is
//! checked before it is returned, so a numerically doubtful pivot sequence is reported
//! as "no solution", never as a wrong one.

use nalgebra::{DMatrix, DVector};

const PIVOT_EPS: f64 = 1e-12;

/// Solves the LCP (M, q). `None` when Lemke's method ends on a ray (no solution for the
/// problems of this crate: the pushers jam the object) or does not converge.
pub fn solve(m: &DMatrix<f64>, q: &DVector<f64>) -> Option<DVector<f64>> {
    let n = q.len();
    if q.iter().all(|&qi| qi >= 0.0) {
        return Some(DVector::zeros(n));
    }
    // Variables: w (0..n), z (n..2n), z0 (2n). Rows: I w - M z - 1 z0 = q, w basic.
    let z0 = 2 * n;
    let mut t = Tableau::new(n);
    for i in 0..n {
        let r = t.row_mut(i);
        for j in 0..n {
            r[j] = -m[(i, j)];
        }
        r[n] = -1.0;
        r[n + 1] = q[i];
    }

    // z0 enters; the most negative q leaves.
    let row = (0..n)
        .min_by(|&a, &b| q[a].total_cmp(&q[b]))
        .expect("n > 0");
    let mut leaving = t.pivot(row, z0);

    for _ in 0..(50 * n + 50) {
        let entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        let col = t.column_of[entering];
        // Minimum ratio test; prefer z0 on ties (ends the method), then larger pivots.
        let mut best: Option<(usize, f64)> = None;
        for i in 0..n {
            let a = t.at(i, col);
            if a > PIVOT_EPS {
                let ratio = t.rhs(i) / a;
                best = match best {
                    None => Some((i, ratio)),
                    Some((bi, br)) => {
                        let tie = (ratio - br).abs() <= 1e-12 * (1.0 + br.abs());
                        let better = if tie {
                            t.basis[i] == z0 || (t.basis[bi] != z0 && a > t.at(bi, col))
                        } else {
                            ratio < br
                        };
                        if better {
                            Some((i, ratio))
                        } else {
                            Some((bi, br))
                        }
                    }
                };
            }
        }
        let (row, _) = best?; // a ray: no solution
        leaving = t.pivot(row, entering);
        if leaving == z0 {
            let mut z = DVector::zeros(n);
            for (i, &b) in t.basis.iter().enumerate() {
                if (n..2 * n).contains(&b) {
                    z[b - n] = t.rhs(i).max(0.0);
                }
            }
            return is_solution(m, q, &z).then_some(z);
        }
    }
    None
}

/// Lemke's tableau with a column for each non-basic variable only (n + 1 of the 2n + 1)
/// and the right-hand side, row by row in one buffer. A basic variable's column is a
/// unit vector, which the full tableau carries along and updates to itself at every
/// pivot; here the leaving variable takes the entering one's column. The arithmetic of
/// every stored entry is the full tableau's, so the pivots and the answer are the same
/// bit for bit, at half the work (BENCHMARKS.md, "Lemke's tableau row by row").
struct Tableau {
    /// n + 2: the non-basic variables' columns, then the right-hand side.
    cols: usize,
    cells: Vec<f64>,
    /// Per row, its basic variable.
    basis: Vec<usize>,
    /// Per variable, its column while it is not basic.
    column_of: Vec<usize>,
}

impl Tableau {
    /// n rows with w basic: columns z (0..n), then z0 (n), then the right-hand side.
    fn new(n: usize) -> Tableau {
        let cols = n + 2;
        let mut column_of = vec![usize::MAX; 2 * n + 1];
        for (c, v) in column_of.iter_mut().skip(n).enumerate() {
            *v = c;
        }
        Tableau {
            cols,
            cells: vec![0.0; n * cols],
            basis: (0..n).collect(),
            column_of,
        }
    }

    fn at(&self, row: usize, col: usize) -> f64 {
        self.cells[row * self.cols + col]
    }

    fn rhs(&self, row: usize) -> f64 {
        self.at(row, self.cols - 1)
    }

    fn row_mut(&mut self, row: usize) -> &mut [f64] {
        &mut self.cells[row * self.cols..(row + 1) * self.cols]
    }

    /// Gauss-Jordan on `row` and `entering`'s column: the pivot row divided by the pivot,
    /// then subtracted from every other row in proportion to its entry in that column,
    /// which the leaving variable's column replaces (the full tableau's unit column after
    /// the same operations: 1 / p in the pivot row, 0 - f / p elsewhere). Returns the
    /// leaving variable.
    fn pivot(&mut self, row: usize, entering: usize) -> usize {
        let cols = self.cols;
        let col = self.column_of[entering];
        let (before, rest) = self.cells.split_at_mut(row * cols);
        let (pivot_row, after) = rest.split_at_mut(cols);
        let p = pivot_row[col];
        for v in pivot_row.iter_mut() {
            *v /= p;
        }
        pivot_row[col] = 1.0 / p;
        for other in before
            .chunks_exact_mut(cols)
            .chain(after.chunks_exact_mut(cols))
        {
            let f = other[col];
            if f != 0.0 {
                other[col] = 0.0;
                for (v, &r) in other.iter_mut().zip(pivot_row.iter()) {
                    *v -= f * r;
                }
            }
        }
        let leaving = std::mem::replace(&mut self.basis[row], entering);
        self.column_of[leaving] = col;
        self.column_of[entering] = usize::MAX;
        leaving
    }
}

/// Feasibility and complementarity within a tolerance scaled to the data.
pub fn is_solution(m: &DMatrix<f64>, q: &DVector<f64>, z: &DVector<f64>) -> bool {
    let w = m * z + q;
    let scale = 1.0 + q.amax() + (m * z).amax();
    let tol = 1e-8 * scale;
    z.iter().all(|&v| v >= -tol)
        && w.iter().all(|&v| v >= -tol)
        && w.iter()
            .zip(z.iter())
            .all(|(a, b)| (a * b).abs() <= tol * (1.0 + b.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_positive_definite_problem_whose_answer_is_known() {
        // M = [[2,1],[1,2]], q = [-5,-6]: both z positive, M z = -q -> z = (4/3, 7/3).
        let m = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
        let q = DVector::from_row_slice(&[-5.0, -6.0]);
        let z = solve(&m, &q).unwrap();
        assert!((z[0] - 4.0 / 3.0).abs() < 1e-12 && (z[1] - 7.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn picks_the_complementary_face() {
        // M = I, q = (-1, 2): z = (1, 0), w = (0, 2).
        let m = DMatrix::identity(2, 2);
        let q = DVector::from_row_slice(&[-1.0, 2.0]);
        let z = solve(&m, &q).unwrap();
        assert_eq!(z.as_slice(), &[1.0, 0.0]);
    }

    /// The LCP's answer by enumeration: for a P-matrix exactly one complementary basis
    /// (a set B with z_B = -M_BB^-1 q_B, z elsewhere zero) has z >= 0 and w >= 0.
    fn enumerated(m: &DMatrix<f64>, q: &DVector<f64>) -> DVector<f64> {
        let n = q.len();
        for set in 0..(1u32 << n) {
            let b: Vec<usize> = (0..n).filter(|i| set & (1 << i) != 0).collect();
            let mut z = DVector::zeros(n);
            if !b.is_empty() {
                let mbb = DMatrix::from_fn(b.len(), b.len(), |i, j| m[(b[i], b[j])]);
                let qb = DVector::from_fn(b.len(), |i, _| -q[b[i]]);
                let Some(zb) = mbb.lu().solve(&qb) else {
                    continue;
                };
                for (k, &i) in b.iter().enumerate() {
                    z[i] = zb[k];
                }
            }
            let w = m * &z + q;
            if z.iter().chain(w.iter()).all(|&v| v >= -1e-12) {
                return z;
            }
        }
        panic!("a P-matrix LCP has a solution");
    }

    #[test]
    fn agrees_with_enumeration_on_random_positive_definite_problems() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for trial in 0..300 {
            let n = 1 + trial % 7;
            // M = A A^T + 0.1 I (positive definite, so a P-matrix) plus a skew part,
            // as friction couples normal and tangent rows unsymmetrically.
            let a = DMatrix::from_fn(n, n, |_, _| rng.random_range(-1.0..1.0));
            let s = DMatrix::from_fn(n, n, |_, _| rng.random_range(-0.5..0.5));
            let m = &a * a.transpose() + DMatrix::identity(n, n) * 0.1 + (&s - s.transpose());
            let q = DVector::from_fn(n, |_, _| rng.random_range(-1.0..1.0));
            let z = solve(&m, &q).expect("a P-matrix LCP has a solution");
            let expected = enumerated(&m, &q);
            assert!(
                (&z - &expected).amax() < 1e-9,
                "trial {trial}: {z} against {expected}"
            );
        }
    }

    #[test]
    fn reports_infeasible_problems() {
        // w = -z - 1 can never be >= 0.
        let m = DMatrix::from_row_slice(1, 1, &[-1.0]);
        let q = DVector::from_row_slice(&[-1.0]);
        assert!(solve(&m, &q).is_none());
    }
}
