//! Lemke's complementary pivoting method for the linear complementarity problem
//!
//! ```text
//! find z >= 0 with w = M z + q >= 0 and w . z = 0.
//! ```
//!
//! Dense tableau, covering vector of ones. The answer is checked before it is returned,
//! so a numerically doubtful pivot sequence is reported as "no solution", never as a
//! wrong one.

use nalgebra::{DMatrix, DVector};

const PIVOT_EPS: f64 = 1e-12;

/// Solves the LCP (M, q). `None` when Lemke's method ends on a ray (no solution for the
/// problems of this crate: the pushers jam the object) or does not converge.
pub fn solve(m: &DMatrix<f64>, q: &DVector<f64>) -> Option<DVector<f64>> {
    let n = q.len();
    if q.iter().all(|&qi| qi >= 0.0) {
        return Some(DVector::zeros(n));
    }
    // Columns: w (0..n), z (n..2n), z0 (2n), rhs (2n+1). Rows: I w - M z - 1 z0 = q.
    let z0 = 2 * n;
    let rhs = 2 * n + 1;
    let mut t = Tableau::new(n, 2 * n + 2);
    for i in 0..n {
        let r = t.row_mut(i);
        r[i] = 1.0;
        for j in 0..n {
            r[n + j] = -m[(i, j)];
        }
        r[z0] = -1.0;
        r[rhs] = q[i];
    }
    let mut basis: Vec<usize> = (0..n).collect();

    // z0 enters; the most negative q leaves.
    let mut row = (0..n)
        .min_by(|&a, &b| q[a].total_cmp(&q[b]))
        .expect("n > 0");
    t.pivot(row, z0);
    let mut leaving = std::mem::replace(&mut basis[row], z0);

    for _ in 0..(50 * n + 50) {
        let entering = if leaving < n {
            leaving + n
        } else {
            leaving - n
        };
        // Minimum ratio test; prefer z0 on ties (ends the method), then larger pivots.
        let mut best: Option<(usize, f64)> = None;
        for i in 0..n {
            let a = t.at(i, entering);
            if a > PIVOT_EPS {
                let ratio = t.at(i, rhs) / a;
                best = match best {
                    None => Some((i, ratio)),
                    Some((bi, br)) => {
                        let tie = (ratio - br).abs() <= 1e-12 * (1.0 + br.abs());
                        let better = if tie {
                            basis[i] == z0 || (basis[bi] != z0 && a > t.at(bi, entering))
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
        let (r, _) = best?; // a ray: no solution
        row = r;
        t.pivot(row, entering);
        leaving = std::mem::replace(&mut basis[row], entering);
        if leaving == z0 {
            let mut z = DVector::zeros(n);
            for (i, &b) in basis.iter().enumerate() {
                if (n..2 * n).contains(&b) {
                    z[b - n] = t.at(i, rhs).max(0.0);
                }
            }
            return is_solution(m, q, &z).then_some(z);
        }
    }
    None
}

/// Lemke's tableau, row by row in one buffer: a pivot sweeps whole rows, which this
/// layout keeps contiguous (nalgebra's matrices are column-major: the same sweep strode
/// across memory and took 40 % of a dense scene's search; BENCHMARKS.md, "Lemke's
/// tableau row by row").
struct Tableau {
    cols: usize,
    cells: Vec<f64>,
}

impl Tableau {
    fn new(rows: usize, cols: usize) -> Tableau {
        Tableau {
            cols,
            cells: vec![0.0; rows * cols],
        }
    }

    fn at(&self, row: usize, col: usize) -> f64 {
        self.cells[row * self.cols + col]
    }

    fn row_mut(&mut self, row: usize) -> &mut [f64] {
        &mut self.cells[row * self.cols..(row + 1) * self.cols]
    }

    /// Gauss-Jordan on (row, col): the pivot row divided by the pivot, then subtracted
    /// from every other row in proportion to its entry in `col`.
    fn pivot(&mut self, row: usize, col: usize) {
        let cols = self.cols;
        let (before, rest) = self.cells.split_at_mut(row * cols);
        let (pivot_row, after) = rest.split_at_mut(cols);
        let p = pivot_row[col];
        for v in pivot_row.iter_mut() {
            *v /= p;
        }
        for other in before
            .chunks_exact_mut(cols)
            .chain(after.chunks_exact_mut(cols))
        {
            let f = other[col];
            if f != 0.0 {
                for (v, &r) in other.iter_mut().zip(pivot_row.iter()) {
                    *v -= f * r;
                }
            }
        }
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

    #[test]
    fn reports_infeasible_problems() {
        // w = -z - 1 can never be >= 0.
        let m = DMatrix::from_row_slice(1, 1, &[-1.0]);
        let q = DVector::from_row_slice(&[-1.0]);
        assert!(solve(&m, &q).is_none());
    }
}
