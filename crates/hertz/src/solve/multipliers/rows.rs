//! The tangent by rows, and the reduced system's rows as they are built.

use crate::assembly::Pattern;

/// Largest difference between an entry and its transpose, relative to the rows' sizes, of a
/// matrix taken as symmetric.
const SYMMETRY_TOL: f64 = 1e-12;

/// A sparse matrix in compressed rows.
pub(super) struct Rows {
    pub(super) ptr: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl Rows {
    /// Both triangles of the matrix `values` on `pattern`, by rows.
    pub(super) fn new(pattern: &Pattern, values: &[f64]) -> Rows {
        let n = pattern.n;
        let mut count = vec![0usize; n + 1];
        for c in 0..n {
            for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                let r = pattern.row_idx[k];
                count[r + 1] += 1;
                if pattern.symmetric && r != c {
                    count[c + 1] += 1;
                }
            }
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let mut next = count.clone();
        let nnz = count[n];
        let (mut col, mut val) = (vec![0; nnz], vec![0.0; nnz]);
        let mut put = |r: usize, c: usize, v: f64| {
            col[next[r]] = c;
            val[next[r]] = v;
            next[r] += 1;
        };
        for c in 0..n {
            for k in pattern.col_ptr[c]..pattern.col_ptr[c + 1] {
                let r = pattern.row_idx[k];
                put(r, c, values[k]);
                if pattern.symmetric && r != c {
                    put(c, r, values[k]);
                }
            }
        }
        Rows {
            ptr: count,
            col,
            val,
        }
    }

    /// Entry (r, c), 0 outside the pattern.
    pub(super) fn at(&self, r: usize, c: usize) -> f64 {
        let cols = &self.col[self.ptr[r]..self.ptr[r + 1]];
        cols.binary_search(&c)
            .map_or(0.0, |k| self.val[self.ptr[r] + k])
    }

    /// Each multiplier's scale, the factor between its row and its column (least squares; a
    /// gap row may be its force column times a factor: a nodal gap against the force's
    /// weighted one), 1 for the other rows; and the multipliers whose column is empty outside
    /// their own rows (open points', which leave the system anyway). None if a row is
    /// orthogonal to its column.
    pub(super) fn multiplier_scales(&self, multipliers: &[usize]) -> Option<(Vec<f64>, Vec<bool>)> {
        let n = self.ptr.len() - 1;
        let mut scale = vec![1.0; n];
        let mut out = vec![false; n];
        for &l in multipliers {
            let (mut rc, mut cc) = (0.0, 0.0);
            for (c, v) in self.row(l) {
                if c != l {
                    let t = self.at(c, l);
                    rc += v * t;
                    cc += t * t;
                }
            }
            if cc == 0.0 {
                out[l] = true;
            } else if rc != 0.0 {
                scale[l] = rc / cc;
            } else {
                return None;
            }
        }
        Some((scale, out))
    }

    /// Whether the matrix is symmetric once each row is divided by its `scale`, but for the
    /// rows and columns `out`: every entry equal to its transpose to 1e-12 of the smaller of
    /// the two rows' largest entries. Symmetric so: small-deformation mortar and node-to-node,
    /// hard constraints.
    pub(super) fn is_symmetric_with(&self, scale: &[f64], out: &[bool]) -> bool {
        let n = self.ptr.len() - 1;
        let size: Vec<f64> = (0..n)
            .map(|i| self.row(i).fold(0.0f64, |m, (_, v)| m.max(v.abs())) / scale[i].abs())
            .collect();
        (0..n).filter(|&i| !out[i]).all(|i| {
            self.row(i).all(|(c, v)| {
                c <= i
                    || out[c]
                    || (v / scale[i] - self.at(c, i) / scale[c]).abs()
                        <= SYMMETRY_TOL * size[i].min(size[c])
            })
        })
    }

    /// y = A x.
    pub(super) fn matvec(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate() {
            *yi = self.row(i).map(|(c, v)| v * x[c]).sum();
        }
    }

    /// The rows divided by `scale`.
    pub(super) fn scaled(&self, scale: &[f64]) -> Rows {
        let mut val = self.val.clone();
        for (i, &s) in scale.iter().enumerate() {
            if s != 1.0 {
                for v in &mut val[self.ptr[i]..self.ptr[i + 1]] {
                    *v /= s;
                }
            }
        }
        Rows {
            ptr: self.ptr.clone(),
            col: self.col.clone(),
            val,
        }
    }

    /// P A Pᵀ ([`super::Transform`]), summed row by row in a dense work row.
    pub(super) fn transformed(&self, t: &super::Transform) -> Rows {
        let n = self.ptr.len() - 1;
        let (mut ptr, mut col, mut val) = (vec![0usize], Vec::new(), Vec::new());
        let mut work = vec![0.0; n];
        let mut used = vec![false; n];
        let mut touched: Vec<usize> = Vec::new();
        for i in 0..n {
            let own = [(i, 1.0)];
            let combination: &[(usize, f64)] = t.rows[i].as_deref().unwrap_or(&own);
            for &(k, pk) in combination {
                for (l, v) in self.row(k) {
                    for &(j, pj) in &t.cols[l] {
                        if !used[j] {
                            used[j] = true;
                            touched.push(j);
                        }
                        work[j] += pk * v * pj;
                    }
                }
            }
            touched.sort_unstable();
            for &j in &touched {
                col.push(j);
                val.push(work[j]);
                work[j] = 0.0;
                used[j] = false;
            }
            touched.clear();
            ptr.push(col.len());
        }
        Rows { ptr, col, val }
    }

    pub(super) fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        (self.ptr[i]..self.ptr[i + 1]).map(|k| (self.col[k], self.val[k]))
    }
}
/// The reduced system's rows, each summed in a dense work row as it is built (the rows of the
/// eliminated slave nodes fill the master rows: a 3D mortar patch's reduced system had 72 million
/// contributions to 3.3 million entries, which as sorted triplets took 20 s and 1.7 GB).
pub(super) struct RowBuilder {
    work: Vec<f64>,
    seen: Vec<bool>,
    cols: Vec<usize>,
    rows: Vec<Vec<(usize, f64)>>,
}

impl RowBuilder {
    pub(super) fn new(n: usize) -> RowBuilder {
        RowBuilder {
            work: vec![0.0; n],
            seen: vec![false; n],
            cols: Vec::new(),
            rows: vec![Vec::new(); n],
        }
    }

    /// Add v at column c of the row being built.
    pub(super) fn add(&mut self, c: usize, v: f64) {
        if !self.seen[c] {
            self.seen[c] = true;
            self.work[c] = 0.0;
            self.cols.push(c);
        }
        self.work[c] += v;
    }

    /// Close the row being built as row t (added to what row t holds already).
    pub(super) fn close(&mut self, t: usize) {
        self.cols.sort_unstable();
        let mut row: Vec<(usize, f64)> = self
            .cols
            .iter()
            .map(|&c| {
                self.seen[c] = false;
                (c, self.work[c])
            })
            .collect();
        self.cols.clear();
        if !self.rows[t].is_empty() {
            row.append(&mut self.rows[t]);
            row.sort_unstable_by_key(|e| e.0);
            row.dedup_by(|b, a| {
                let same = a.0 == b.0;
                if same {
                    a.1 += b.1;
                }
                same
            });
        }
        self.rows[t] = row;
    }

    /// The rows built, as a matrix by rows.
    pub(super) fn into_rows(self) -> Rows {
        let mut ptr = Vec::with_capacity(self.rows.len() + 1);
        ptr.push(0);
        let (mut col, mut val) = (Vec::new(), Vec::new());
        for row in self.rows {
            for (c, v) in row {
                col.push(c);
                val.push(v);
            }
            ptr.push(col.len());
        }
        Rows { ptr, col, val }
    }

    /// The upper triangle of a symmetric matrix whose rows hold their entries on and right of
    /// the diagonal (the diagonal always present), by columns.
    pub(super) fn into_upper_pattern(self) -> (Pattern, Vec<f64>) {
        let n = self.rows.len();
        let mut by_col: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for (r, row) in self.rows.iter().enumerate() {
            if row.first().is_none_or(|e| e.0 != r) {
                by_col[r].push((r, 0.0));
            }
            for &(c, v) in row {
                debug_assert!(c >= r, "entry left of the diagonal");
                by_col[c].push((r, v));
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let (mut row_idx, mut vals) = (Vec::new(), Vec::new());
        col_ptr.push(0);
        for entries in by_col {
            for (r, v) in entries {
                row_idx.push(r);
                vals.push(v);
            }
            col_ptr.push(row_idx.len());
        }
        (
            Pattern {
                n,
                col_ptr,
                row_idx,
                symmetric: true,
            },
            vals,
        )
    }

    /// A general, structurally symmetric pattern (diagonal always present; the Krylov solver's
    /// preconditioner takes the symmetric part on it) and its values, by columns.
    pub(super) fn into_pattern(self) -> (Pattern, Vec<f64>) {
        let n = self.rows.len();
        // Column c holds the entries (r, c) of row r and, with zeros, the transposed ones of
        // row c, and the diagonal.
        let mut by_col: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for (r, row) in self.rows.iter().enumerate() {
            for &(c, v) in row {
                by_col[c].push((r, v));
            }
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        let (mut row_idx, mut vals) = (Vec::new(), Vec::new());
        col_ptr.push(0);
        for (c, entries) in by_col.iter().enumerate() {
            // Merge the column's entries (rows ascending) with row c's columns and c itself.
            let transposed = self.rows[c].iter().map(|e| (e.0, 0.0));
            let mut merged: Vec<(usize, f64)> = entries
                .iter()
                .copied()
                .chain(transposed)
                .chain(std::iter::once((c, 0.0)))
                .collect();
            merged.sort_unstable_by_key(|e| e.0);
            for (r, v) in merged {
                if row_idx.len() > col_ptr[c] && row_idx.last() == Some(&r) {
                    *vals.last_mut().expect("an entry") += v;
                } else {
                    row_idx.push(r);
                    vals.push(v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        (
            Pattern {
                n,
                col_ptr,
                row_idx,
                symmetric: false,
            },
            vals,
        )
    }
}
