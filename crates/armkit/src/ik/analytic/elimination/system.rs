//! One target's eliminated system: the equations' matrix, its
//! determinant in joint 3 and the null vector giving joints 4-5
//! (Manocha and Canny's 12 x 12 matrix `Sigma`).

use super::{Square, DOUBLE_NULL, FUNCTIONS, HALF_ANGLE};
use crate::math::sin_cos;

/// One target's eliminated equations and the QR's triangle.
pub(super) struct System {
    /// Six equations; `[i3][3 a + b]` the coefficient of `x4^a x5^b` times
    /// `m3[i3]`.
    pub(super) equations: [[[f64; 9]; 3]; 6],
    /// After the Householder QR: rows 0..8 hold `R` (columns 0..8) and
    /// `Y' P`, `Y' q0` (columns 8..35, 35); rows 8..14 the eliminated
    /// equations.
    pub(super) upper: [[f64; 36]; FUNCTIONS],
}

impl System {
    /// `det Sigma(q3)` at `q3` (rad).
    pub(super) fn determinant(&self, q3: f64) -> f64 {
        let (s, c) = sin_cos(q3);
        self.determinant_at(c, s)
    }

    /// `det Sigma(q3)` at `(cos q3, sin q3)`, by [`shifted_determinant`].
    pub(super) fn determinant_at(&self, c3: f64, s3: f64) -> f64 {
        shifted_determinant(&self.equations_at(c3, s3))
    }

    /// The six equations at `(cos q3, sin q3)`: `[k][3 a + b]` the
    /// coefficient of `x4^a x5^b`.
    pub(super) fn equations_at(&self, c3: f64, s3: f64) -> [[f64; 9]; 6] {
        let mut at = [[0.0; 9]; 6];
        for (row, equation) in at.iter_mut().zip(&self.equations) {
            let [constant, cosine, sine] = equation;
            for (i, value) in row.iter_mut().enumerate() {
                *value = constant[i] + c3 * cosine[i] + s3 * sine[i];
            }
        }
        at
    }

    /// `Sigma(q3)` at `(cos q3, sin q3)`: rows 0..6 the equations, rows
    /// 6..12 the same times `x4`; column `3 a + b` is `x4^a x5^b`.
    pub(super) fn sigma(&self, c3: f64, s3: f64) -> Square {
        let mut sigma = [[0.0; 12]; 12];
        for (k, row) in self.equations_at(c3, s3).iter().enumerate() {
            sigma[k][..9].copy_from_slice(row);
            sigma[6 + k][3..].copy_from_slice(row);
        }
        sigma
    }
}

/// `det Sigma` from the six equations `a` (6 x 9: blocks `A0 A1 A2` of the
/// powers of `x4`), using its shifted structure `Sigma = [A0 A1 A2 0; 0 A0
/// A1 A2]`: Gaussian elimination with row pivoting of `A0`'s three columns,
/// applied to all of `a` (an operation on both block rows at once, of
/// determinant +-1 squared), leaves `[U0 B1 B2 0; 0 C1 C2 0; 0 U0 B1 B2;
/// 0 0 C1 C2]`, whose determinant is `det U0` times that of the 9 x 9
/// `[C1 C2 0; U0 B1 B2; 0 C1 C2]`. About two thirds of the dense 12 x 12
/// elimination's work; checked against it in the tests.
pub(super) fn shifted_determinant(a: &[[f64; 9]; 6]) -> f64 {
    let mut a = *a;
    let mut determinant = 1.0;
    for k in 0..3 {
        let pivot_row = (k..6)
            .max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))
            .unwrap_or(k);
        // The same swap in both block rows: its sign counts twice.
        a.swap(pivot_row, k);
        let pivot = a[k][k];
        if pivot == 0.0 {
            return 0.0;
        }
        determinant *= pivot;
        let (above, below) = a.split_at_mut(k + 1);
        let pivot_values = &above[k][k + 1..];
        let inverse = 1.0 / pivot;
        for row in below.iter_mut() {
            let factor = row[k] * inverse;
            for (value, above) in row[k + 1..].iter_mut().zip(pivot_values) {
                *value -= factor * above;
            }
        }
    }
    // Rows 3..6 of `a` hold [0 C1 C2], rows 0..3 [U0 B1 B2] (the
    // elimination left the eliminated entries, zero in `U0`, unwritten).
    let mut m = [[0.0; 9]; 9];
    for i in 0..3 {
        m[i][..6].copy_from_slice(&a[3 + i][3..]);
        m[3 + i][i..].copy_from_slice(&a[i][i..]);
        m[6 + i][3..].copy_from_slice(&a[3 + i][3..]);
    }
    determinant * dense_determinant(&mut m)
}

/// The determinant of an n x n matrix (destroyed): Gaussian elimination
/// with row pivoting.
pub(super) fn dense_determinant<const N: usize>(a: &mut [[f64; N]; N]) -> f64 {
    let mut determinant = 1.0;
    for k in 0..N {
        let mut pivot_row = k;
        for i in k + 1..N {
            if a[i][k].abs() > a[pivot_row][k].abs() {
                pivot_row = i;
            }
        }
        if pivot_row != k {
            a.swap(pivot_row, k);
            determinant = -determinant;
        }
        let pivot = a[k][k];
        determinant *= pivot;
        if pivot == 0.0 {
            return 0.0;
        }
        let (above, below) = a.split_at_mut(k + 1);
        let pivot_values = &above[k][k + 1..];
        let inverse = 1.0 / pivot;
        for row in below.iter_mut() {
            if row[k] == 0.0 {
                continue;
            }
            let factor = row[k] * inverse;
            for (value, above) in row[k + 1..].iter_mut().zip(pivot_values) {
                *value -= factor * above;
            }
        }
    }
    determinant
}

/// Turns values on the grid `(0, pi/2, pi)` along one index of stride
/// `stride` (of a 3 x 3 (x 3) tensor) into coefficients of
/// `(1, cos, sin)`: `1 = (v0 + v2)/2`, `cos = (v0 - v2)/2`,
/// `sin = v1 - (v0 + v2)/2`.
pub(super) fn coefficients_along(values: &mut [f64], stride: usize) {
    let size = values.len();
    for start in 0..size {
        if (start / stride) % 3 != 0 {
            continue;
        }
        let (v0, v1, v2) = (
            values[start],
            values[start + stride],
            values[start + 2 * stride],
        );
        let mean = 0.5 * (v0 + v2);
        values[start] = mean;
        values[start + stride] = 0.5 * (v0 - v2);
        values[start + 2 * stride] = v1 - mean;
    }
}

/// Coefficients over `m4 (x) m5` (index `3 i4 + i5`) as coefficients of
/// `x4^a x5^b` (index `3 a + b`) after multiplying by `(1+x4^2)(1+x5^2)`.
pub(super) fn half_angle_form(coefficients: &[f64]) -> [f64; 9] {
    let mut out = [0.0; 9];
    for i4 in 0..3 {
        for i5 in 0..3 {
            let value = coefficients[3 * i4 + i5];
            for a in 0..3 {
                for b in 0..3 {
                    out[3 * a + b] += value * HALF_ANGLE[i4][a] * HALF_ANGLE[i5][b];
                }
            }
        }
    }
    out
}

/// Each of the six equations scaled to a unit coefficient vector (the
/// same solutions; a determinant of order 1).
pub(super) fn normalize(equations: &mut [[[f64; 9]; 3]; 6]) {
    for equation in equations.iter_mut() {
        let norm = equation.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 0.0 {
            equation.iter_mut().flatten().for_each(|x| *x /= norm);
        }
    }
}

/// `m3 (x) m4 (x) m5` (index `9 i3 + 3 i4 + i5`).
pub(super) fn tensor3(q3: f64, q4: f64, q5: f64) -> [f64; 27] {
    let m = |q: f64| {
        let (s, c) = sin_cos(q);
        [1.0, c, s]
    };
    let (m3, m4, m5) = (m(q3), m(q4), m(q5));
    let mut out = [0.0; 27];
    for a in 0..3 {
        for b in 0..3 {
            for d in 0..3 {
                out[9 * a + 3 * b + d] = m3[a] * m4[b] * m5[d];
            }
        }
    }
    out
}

/// Householder QR of the first 8 columns of `m`, applied to all 36: after
/// it, `m = Y' m` with `Y' m[.., 0..8]` upper triangular.
pub(super) fn householder(m: &mut [[f64; 36]; FUNCTIONS]) {
    for k in 0..8 {
        let norm = (k..FUNCTIONS)
            .map(|i| m[i][k] * m[i][k])
            .sum::<f64>()
            .sqrt();
        if norm == 0.0 {
            continue;
        }
        let alpha = if m[k][k] > 0.0 { -norm } else { norm };
        let mut v = [0.0; FUNCTIONS];
        for i in k..FUNCTIONS {
            v[i] = m[i][k];
        }
        v[k] -= alpha;
        let vv: f64 = v[k..].iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        // m -= v (2 v'm / v'v), row by row (the rows are contiguous).
        let mut dots = [0.0; 36];
        for (row, vi) in m[k..].iter().zip(&v[k..]) {
            for (dot, value) in dots[k..].iter_mut().zip(&row[k..]) {
                *dot += vi * value;
            }
        }
        let scale = 2.0 / vv;
        for (row, vi) in m[k..].iter_mut().zip(&v[k..]) {
            let factor = scale * vi;
            for (value, dot) in row[k..].iter_mut().zip(&dots[k..]) {
                *value -= factor * dot;
            }
        }
    }
}

/// The null space of a (nearly) singular 12 x 12 matrix: Gaussian
/// elimination with full pivoting over 11 pivots.
pub(super) struct NullSpace {
    /// The upper triangle (columns permuted).
    pub(super) upper: Square,
    /// `columns[j]`: the original column at position `j`.
    pub(super) columns: [usize; 12],
}

impl NullSpace {
    pub(super) fn of(matrix: &Square) -> NullSpace {
        let mut upper = *matrix;
        let mut columns = [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11];
        for k in 0..11 {
            let (mut row, mut column, mut largest) = (k, k, 0.0);
            for (i, values) in upper[k..].iter().enumerate() {
                for (j, value) in values[k..].iter().enumerate() {
                    if value.abs() > largest {
                        (row, column, largest) = (k + i, k + j, value.abs());
                    }
                }
            }
            upper.swap(row, k);
            for values in upper.iter_mut() {
                values.swap(column, k);
            }
            columns.swap(column, k);
            let pivot = upper[k][k];
            if pivot == 0.0 {
                continue;
            }
            let pivot_row = upper[k];
            for row in upper[k + 1..].iter_mut() {
                let factor = row[k] / pivot;
                for (value, above) in row[k..].iter_mut().zip(&pivot_row[k..]) {
                    *value -= factor * above;
                }
            }
        }
        NullSpace { upper, columns }
    }

    /// Whether the eleventh pivot is below [`DOUBLE_NULL`] of the first:
    /// the null space is (nearly) two-dimensional.
    pub(super) fn is_double(&self) -> bool {
        self.upper[10][10].abs() <= DOUBLE_NULL * self.upper[0][0].abs()
    }

    /// The null vector: the last pivoted unknown 1.
    pub(super) fn vector(&self) -> [f64; 12] {
        let mut y = [0.0; 12];
        y[11] = 1.0;
        self.completed(y, 11)
    }

    /// A basis of the two-dimensional null space: the last two pivoted
    /// unknowns (1, 0) and (0, 1).
    pub(super) fn pair(&self) -> [[f64; 12]; 2] {
        let mut first = [0.0; 12];
        first[10] = 1.0;
        let mut second = [0.0; 12];
        second[11] = 1.0;
        [self.completed(first, 10), self.completed(second, 10)]
    }

    /// `y` (pivoted order) with its first `solved` unknowns back-substituted
    /// from the rest, in the original order.
    pub(super) fn completed(&self, mut y: [f64; 12], solved: usize) -> [f64; 12] {
        let u = &self.upper;
        for i in (0..solved).rev() {
            let known: f64 = (i + 1..12).map(|j| u[i][j] * y[j]).sum();
            y[i] = -known / u[i][i];
        }
        let mut v = [0.0; 12];
        for (j, value) in y.iter().enumerate() {
            v[self.columns[j]] = *value;
        }
        v
    }
}

/// The monomial vectors `(x4^a x5^b)` in a two-dimensional null space
/// `basis` (two solutions sharing joint 3): `v = N c` with `v[3 (a + 1) + b]
/// = x4 v[3 a + b]`, a 2 x 2 eigenproblem `(A'A)^-1 A'B c = x4 c` over the
/// shifted rows (least squares); `None` for a complex pair.
pub(super) fn monomials_in(basis: &[[f64; 12]; 2]) -> Option<[[f64; 12]; 2]> {
    let (mut gram, mut cross) = ([[0.0; 2]; 2], [[0.0; 2]; 2]);
    for i in 0..9 {
        for r in 0..2 {
            for c in 0..2 {
                gram[r][c] += basis[r][i] * basis[c][i];
                cross[r][c] += basis[r][i] * basis[c][i + 3];
            }
        }
    }
    let det = gram[0][0] * gram[1][1] - gram[0][1] * gram[1][0];
    if det == 0.0 {
        return None;
    }
    // M = gram^-1 cross.
    let inverse = [
        [gram[1][1] / det, -gram[0][1] / det],
        [-gram[1][0] / det, gram[0][0] / det],
    ];
    let mut m = [[0.0; 2]; 2];
    for r in 0..2 {
        for c in 0..2 {
            m[r][c] = inverse[r][0] * cross[0][c] + inverse[r][1] * cross[1][c];
        }
    }
    let half_trace = 0.5 * (m[0][0] + m[1][1]);
    let discriminant = half_trace * half_trace - (m[0][0] * m[1][1] - m[0][1] * m[1][0]);
    if discriminant < 0.0 {
        return None;
    }
    let eigenvector = |lambda: f64| {
        if m[0][1].abs() > m[1][0].abs() {
            [m[0][1], lambda - m[0][0]]
        } else {
            [lambda - m[1][1], m[1][0]]
        }
    };
    let root = discriminant.sqrt();
    Some([half_trace + root, half_trace - root].map(|lambda| {
        let c = eigenvector(lambda);
        std::array::from_fn(|i| basis[0][i] * c[0] + basis[1][i] * c[1])
    }))
}
