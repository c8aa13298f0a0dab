//! Shape functions in OOFEM's node orderings (spec §1.9) and the element boundaries.

/// Reference element shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shape {
    /// 2 nodes on ξ ∈ [−1, 1].
    Line2,
    /// 3 nodes on ξ ∈ [−1, 1]: ends then middle (edge of an 8-node quad).
    Line3,
    /// N = (ξ, η, 1−ξ−η).
    Tri3,
    /// Quadratic triangle in the barycentrics (l1, l2, l3) = (ξ, η, 1−ξ−η): corners 1–3 as
    /// Tri3, mid-side 4 (1–2), 5 (2–3), 6 (3–1).
    Tri6,
    /// Node 1 at (+1,+1), 2 (−1,+1), 3 (−1,−1), 4 (+1,−1).
    Quad4,
    /// Corners as Quad4, mid-side 5 (1–2), 6 (2–3), 7 (3–4), 8 (4–1).
    Quad8,
    /// N = (ξ, η, ζ, 1−ξ−η−ζ).
    Tet4,
    /// Quadratic tetrahedron (OOFEM's QTRSpace) in the barycentrics (l1..l4) = (ξ, η, ζ,
    /// 1−ξ−η−ζ): corners 1–4 as Tet4, mid-edge 5 (1–2), 6 (2–3), 7 (3–1), 8 (1–4), 9 (2–4),
    /// 10 (3–4).
    Tet10,
    /// Nodes 1..8 at (−1,−1,+1), (−1,+1,+1), (+1,+1,+1), (+1,−1,+1), then the same at ζ = −1.
    Hexa8,
    /// 20-node serendipity hexahedron (OOFEM's QSpace): corners as Hexa8, then mid-edge nodes
    /// 9–12 on 1–2, 2–3, 3–4, 4–1, 13–16 on 5–6, 6–7, 7–8, 8–5, 17–20 on 1–5, 2–6, 3–7, 4–8.
    Hexa20,
    /// N₁..₃ = ½(1−w)(1−u−v, u, v), N₄..₆ = ½(1+w)(1−u−v, u, v).
    Wedge6,
}

const QUAD4_NODES: [[f64; 2]; 4] = [[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]];
const QUAD8_NODES: [[f64; 2]; 8] = [
    [1.0, 1.0],
    [-1.0, 1.0],
    [-1.0, -1.0],
    [1.0, -1.0],
    [0.0, 1.0],
    [-1.0, 0.0],
    [0.0, -1.0],
    [1.0, 0.0],
];
const HEXA8_NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [1.0, 1.0, 1.0],
    [1.0, -1.0, 1.0],
    [-1.0, -1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [1.0, 1.0, -1.0],
    [1.0, -1.0, -1.0],
];

/// Corners of the unit cube \[0,1\]³ in OOFEM's LSpace node order (node a at `HEXA8_CORNERS[a]`),
/// for generating brick meshes.
pub const HEXA8_CORNERS: [[usize; 3]; 8] = {
    let mut c = [[0usize; 3]; 8];
    let mut a = 0;
    while a < 8 {
        let mut i = 0;
        while i < 3 {
            c[a][i] = if HEXA8_NODES[a][i] > 0.0 { 1 } else { 0 };
            i += 1;
        }
        a += 1;
    }
    c
};

impl Shape {
    /// Dimension of the reference domain.
    pub fn dim(self) -> usize {
        match self {
            Shape::Line2 | Shape::Line3 => 1,
            Shape::Tri3 | Shape::Tri6 | Shape::Quad4 | Shape::Quad8 => 2,
            Shape::Tet4 | Shape::Tet10 | Shape::Hexa8 | Shape::Hexa20 | Shape::Wedge6 => 3,
        }
    }

    pub fn n_nodes(self) -> usize {
        match self {
            Shape::Line2 => 2,
            Shape::Line3 | Shape::Tri3 => 3,
            Shape::Quad4 | Shape::Tet4 => 4,
            Shape::Tri6 | Shape::Wedge6 => 6,
            Shape::Quad8 | Shape::Hexa8 => 8,
            Shape::Tet10 => 10,
            Shape::Hexa20 => 20,
        }
    }

    /// The reference element's centroid.
    pub fn centroid(self) -> [f64; 3] {
        match self {
            Shape::Tri3 | Shape::Tri6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
            Shape::Tet4 | Shape::Tet10 => [0.25, 0.25, 0.25],
            Shape::Wedge6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
            _ => [0.0; 3],
        }
    }

    /// Evaluate N_a(ξ) into `n` and ∂N_a/∂ξ_k into `dn[a][k]`.
    pub fn eval(self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        match self.dim() {
            3 => self.eval_solid(xi, n, dn),
            _ => self.eval_plane(xi, n, dn),
        }
    }

    /// [`Shape::eval`] of lines and plane shapes.
    fn eval_plane(self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        let [x, y, _] = xi;
        match self {
            Shape::Line2 => {
                n[0] = 0.5 * (1.0 - x);
                n[1] = 0.5 * (1.0 + x);
                dn[0] = [-0.5, 0.0, 0.0];
                dn[1] = [0.5, 0.0, 0.0];
            }
            Shape::Line3 => {
                n[0] = 0.5 * x * (x - 1.0);
                n[1] = 0.5 * x * (x + 1.0);
                n[2] = 1.0 - x * x;
                dn[0] = [x - 0.5, 0.0, 0.0];
                dn[1] = [x + 0.5, 0.0, 0.0];
                dn[2] = [-2.0 * x, 0.0, 0.0];
            }
            Shape::Tri3 => {
                n[0] = x;
                n[1] = y;
                n[2] = 1.0 - x - y;
                dn[0] = [1.0, 0.0, 0.0];
                dn[1] = [0.0, 1.0, 0.0];
                dn[2] = [-1.0, -1.0, 0.0];
            }
            Shape::Tri6 => {
                let l = [x, y, 1.0 - x - y];
                let dl = [[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]];
                for i in 0..3 {
                    n[i] = (2.0 * l[i] - 1.0) * l[i];
                    let f = 4.0 * l[i] - 1.0;
                    dn[i] = [f * dl[i][0], f * dl[i][1], 0.0];
                    let j = (i + 1) % 3;
                    n[3 + i] = 4.0 * l[i] * l[j];
                    dn[3 + i] = [
                        4.0 * (dl[i][0] * l[j] + l[i] * dl[j][0]),
                        4.0 * (dl[i][1] * l[j] + l[i] * dl[j][1]),
                        0.0,
                    ];
                }
            }
            Shape::Quad4 => {
                for (a, p) in QUAD4_NODES.iter().enumerate() {
                    n[a] = 0.25 * (1.0 + p[0] * x) * (1.0 + p[1] * y);
                    dn[a] = [
                        0.25 * p[0] * (1.0 + p[1] * y),
                        0.25 * p[1] * (1.0 + p[0] * x),
                        0.0,
                    ];
                }
            }
            Shape::Quad8 => {
                for (a, p) in QUAD8_NODES.iter().enumerate() {
                    let (px, py) = (p[0], p[1]);
                    if a < 4 {
                        let s = px * x + py * y - 1.0;
                        n[a] = 0.25 * (1.0 + px * x) * (1.0 + py * y) * s;
                        dn[a] = [
                            0.25 * px * (1.0 + py * y) * (s + 1.0 + px * x),
                            0.25 * py * (1.0 + px * x) * (s + 1.0 + py * y),
                            0.0,
                        ];
                    } else if px == 0.0 {
                        n[a] = 0.5 * (1.0 - x * x) * (1.0 + py * y);
                        dn[a] = [-x * (1.0 + py * y), 0.5 * py * (1.0 - x * x), 0.0];
                    } else {
                        n[a] = 0.5 * (1.0 + px * x) * (1.0 - y * y);
                        dn[a] = [0.5 * px * (1.0 - y * y), -y * (1.0 + px * x), 0.0];
                    }
                }
            }
            _ => unreachable!("a line or plane shape"),
        }
    }

    /// [`Shape::eval`] of solid shapes.
    fn eval_solid(self, xi: [f64; 3], n: &mut [f64], dn: &mut [[f64; 3]]) {
        let [x, y, z] = xi;
        match self {
            Shape::Tet4 => {
                n[0] = x;
                n[1] = y;
                n[2] = z;
                n[3] = 1.0 - x - y - z;
                dn[0] = [1.0, 0.0, 0.0];
                dn[1] = [0.0, 1.0, 0.0];
                dn[2] = [0.0, 0.0, 1.0];
                dn[3] = [-1.0, -1.0, -1.0];
            }
            Shape::Tet10 => {
                let l = [x, y, z, 1.0 - x - y - z];
                let dl = [
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                    [-1.0, -1.0, -1.0],
                ];
                for i in 0..4 {
                    n[i] = (2.0 * l[i] - 1.0) * l[i];
                    let f = 4.0 * l[i] - 1.0;
                    dn[i] = [f * dl[i][0], f * dl[i][1], f * dl[i][2]];
                }
                // Mid-edge node 5 + k on Tet4's edge k.
                for (k, e) in Shape::Tet4.edges().iter().enumerate() {
                    let (i, j) = (e[0], e[1]);
                    n[4 + k] = 4.0 * l[i] * l[j];
                    dn[4 + k] = std::array::from_fn(|c| 4.0 * (dl[i][c] * l[j] + l[i] * dl[j][c]));
                }
            }
            Shape::Hexa8 => {
                for (a, p) in HEXA8_NODES.iter().enumerate() {
                    let (fx, fy, fz) = (1.0 + p[0] * x, 1.0 + p[1] * y, 1.0 + p[2] * z);
                    n[a] = 0.125 * fx * fy * fz;
                    dn[a] = [
                        0.125 * p[0] * fy * fz,
                        0.125 * p[1] * fx * fz,
                        0.125 * p[2] * fx * fy,
                    ];
                }
            }
            Shape::Hexa20 => {
                for (a, p) in HEXA8_NODES.iter().enumerate() {
                    let (fx, fy, fz) = (1.0 + p[0] * x, 1.0 + p[1] * y, 1.0 + p[2] * z);
                    let s = p[0] * x + p[1] * y + p[2] * z - 2.0;
                    n[a] = 0.125 * fx * fy * fz * s;
                    dn[a] = [
                        0.125 * p[0] * fy * fz * (s + fx),
                        0.125 * p[1] * fx * fz * (s + fy),
                        0.125 * p[2] * fx * fy * (s + fz),
                    ];
                }
                // A mid-edge node: the coordinate along its edge is 0 (quadratic bubble there).
                for (k, e) in Shape::Hexa8.edges().iter().enumerate() {
                    let (i, j) = (e[0], e[1]);
                    let m: [f64; 3] =
                        std::array::from_fn(|c| 0.5 * (HEXA8_NODES[i][c] + HEXA8_NODES[j][c]));
                    let along = (0..3).find(|&c| m[c] == 0.0).expect("an edge's free axis");
                    let xi = [x, y, z];
                    let mut f = [0.0; 3];
                    let mut df = [0.0; 3];
                    for c in 0..3 {
                        if c == along {
                            f[c] = 1.0 - xi[c] * xi[c];
                            df[c] = -2.0 * xi[c];
                        } else {
                            f[c] = 1.0 + m[c] * xi[c];
                            df[c] = m[c];
                        }
                    }
                    n[8 + k] = 0.25 * f[0] * f[1] * f[2];
                    dn[8 + k] = [
                        0.25 * df[0] * f[1] * f[2],
                        0.25 * f[0] * df[1] * f[2],
                        0.25 * f[0] * f[1] * df[2],
                    ];
                }
            }
            Shape::Wedge6 => {
                let tri = [1.0 - x - y, x, y];
                let dtri = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
                for i in 0..3 {
                    for (half, s) in [(0usize, -1.0f64), (3, 1.0)] {
                        let a = i + half;
                        let fz = 0.5 * (1.0 + s * z);
                        n[a] = fz * tri[i];
                        dn[a] = [fz * dtri[i][0], fz * dtri[i][1], 0.5 * s * tri[i]];
                    }
                }
            }
            _ => unreachable!("a solid shape"),
        }
    }

    /// How far the reference point `xi` lies inside the reference element, in reference
    /// coordinates: the smallest distance to a side of its parameter domain (negative outside).
    pub fn inside_margin(self, xi: [f64; 3]) -> f64 {
        let [x, y, z] = xi;
        match self {
            Shape::Line2 | Shape::Line3 => 1.0 - x.abs(),
            Shape::Tri3 | Shape::Tri6 => x.min(y).min(1.0 - x - y),
            Shape::Quad4 | Shape::Quad8 => (1.0 - x.abs()).min(1.0 - y.abs()),
            Shape::Tet4 | Shape::Tet10 => x.min(y).min(z).min(1.0 - x - y - z),
            Shape::Hexa8 | Shape::Hexa20 => (1.0 - x.abs()).min(1.0 - y.abs()).min(1.0 - z.abs()),
            Shape::Wedge6 => x.min(y).min(1.0 - x - y).min(1.0 - z.abs()),
        }
    }

    /// Centre of the reference element.
    pub fn centre(self) -> [f64; 3] {
        match self {
            Shape::Tri3 | Shape::Tri6 | Shape::Wedge6 => [1.0 / 3.0, 1.0 / 3.0, 0.0],
            Shape::Tet4 | Shape::Tet10 => [0.25, 0.25, 0.25],
            _ => [0.0; 3],
        }
    }

    /// Node permutation that mirrors an element (node a of the mirror is node `mirror()[a]`):
    /// the same element with the opposite orientation (det J of the other sign).
    pub fn mirror(self) -> &'static [usize] {
        match self {
            Shape::Line2 => &[1, 0],
            Shape::Line3 => &[1, 0, 2],
            Shape::Tri3 => &[0, 2, 1],
            Shape::Tri6 => &[0, 2, 1, 5, 4, 3],
            Shape::Quad4 => &[0, 3, 2, 1],
            Shape::Quad8 => &[0, 3, 2, 1, 7, 6, 5, 4],
            Shape::Tet4 => &[0, 2, 1, 3],
            Shape::Tet10 => &[0, 2, 1, 3, 6, 5, 4, 7, 9, 8],
            Shape::Hexa8 => &[4, 5, 6, 7, 0, 1, 2, 3],
            // Swapping the two faces: edges 9–12 ↔ 13–16, the vertical ones stay.
            Shape::Hexa20 => &[
                4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11, 16, 17, 18, 19,
            ],
            Shape::Wedge6 => &[3, 4, 5, 0, 1, 2],
        }
    }

    /// Local node lists of the element boundaries (edges in 2D, faces in 3D), 1-based numbering
    /// as in OOFEM (spec §1.9). Quad8 and Tri6 edges list (first corner, second corner, mid-side).
    pub fn boundaries(self) -> &'static [&'static [usize]] {
        match self {
            Shape::Line2 | Shape::Line3 => &[&[0], &[1]],
            Shape::Tri3 => &[&[0, 1], &[1, 2], &[2, 0]],
            Shape::Tri6 => &[&[0, 1, 3], &[1, 2, 4], &[2, 0, 5]],
            Shape::Quad4 => &[&[0, 1], &[1, 2], &[2, 3], &[3, 0]],
            Shape::Quad8 => &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]],
            Shape::Tet4 => &[&[0, 2, 1], &[0, 1, 3], &[1, 2, 3], &[0, 3, 2]],
            // Tet4's faces with their mid-edge nodes (Tri6 order: corners, then the mid-sides
            // of the face's sides 1–2, 2–3, 3–1).
            Shape::Tet10 => &[
                &[0, 2, 1, 6, 5, 4],
                &[0, 1, 3, 4, 8, 7],
                &[1, 2, 3, 5, 9, 8],
                &[0, 3, 2, 7, 9, 6],
            ],
            Shape::Hexa8 => &[
                &[0, 3, 2, 1],
                &[4, 5, 6, 7],
                &[0, 1, 5, 4],
                &[1, 2, 6, 5],
                &[2, 3, 7, 6],
                &[3, 0, 4, 7],
            ],
            // Hexa8's faces with their mid-edge nodes (Quad8 order: corners, then the mid-sides of
            // the face's sides 1–2, 2–3, 3–4, 4–1).
            Shape::Hexa20 => &[
                &[0, 3, 2, 1, 11, 10, 9, 8],
                &[4, 5, 6, 7, 12, 13, 14, 15],
                &[0, 1, 5, 4, 8, 17, 12, 16],
                &[1, 2, 6, 5, 9, 18, 13, 17],
                &[2, 3, 7, 6, 10, 19, 14, 18],
                &[3, 0, 4, 7, 11, 16, 15, 19],
            ],
            Shape::Wedge6 => &[
                &[0, 1, 2],
                &[3, 4, 5],
                &[0, 1, 4, 3],
                &[1, 2, 5, 4],
                &[2, 0, 3, 5],
            ],
        }
    }

    /// Edges of 3D elements (used by `elementedges` on 3D elements); 2D: same as boundaries.
    pub fn edges(self) -> &'static [&'static [usize]] {
        match self {
            Shape::Tet4 => &[&[0, 1], &[1, 2], &[2, 0], &[0, 3], &[1, 3], &[2, 3]],
            Shape::Tet10 => &[
                &[0, 1, 4],
                &[1, 2, 5],
                &[2, 0, 6],
                &[0, 3, 7],
                &[1, 3, 8],
                &[2, 3, 9],
            ],
            Shape::Hexa8 => &[
                &[0, 1],
                &[1, 2],
                &[2, 3],
                &[3, 0],
                &[4, 5],
                &[5, 6],
                &[6, 7],
                &[7, 4],
                &[0, 4],
                &[1, 5],
                &[2, 6],
                &[3, 7],
            ],
            Shape::Hexa20 => &[
                &[0, 1, 8],
                &[1, 2, 9],
                &[2, 3, 10],
                &[3, 0, 11],
                &[4, 5, 12],
                &[5, 6, 13],
                &[6, 7, 14],
                &[7, 4, 15],
                &[0, 4, 16],
                &[1, 5, 17],
                &[2, 6, 18],
                &[3, 7, 19],
            ],
            Shape::Wedge6 => &[
                &[0, 1],
                &[1, 2],
                &[2, 0],
                &[3, 4],
                &[4, 5],
                &[5, 3],
                &[0, 3],
                &[1, 4],
                &[2, 5],
            ],
            s => s.boundaries(),
        }
    }

    /// Shape of a boundary (edge or face) with `n` nodes of this element: 2 → Line2, 3 → Line3
    /// on a 2D element (quadratic edge) or Tri3 on a 3D one, 4 → Quad4, 6 → Tri6, 8 → Quad8 (a
    /// face of a 3D element).
    pub fn boundary_shape(self, n: usize) -> Shape {
        match (self.dim(), n) {
            (2, 3) => Shape::Line3,
            (3, 3) => Shape::Tri3,
            (_, 4) => Shape::Quad4,
            (_, 6) => Shape::Tri6,
            (3, 8) => Shape::Quad8,
            _ => Shape::Line2,
        }
    }

    /// Shape of an edge with `n` nodes (of `edges()`): 2 → Line2, 3 → Line3.
    pub fn edge_shape(n: usize) -> Shape {
        if n == 3 {
            Shape::Line3
        } else {
            Shape::Line2
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Shape; 11] = [
        Shape::Line2,
        Shape::Line3,
        Shape::Tri3,
        Shape::Tri6,
        Shape::Quad4,
        Shape::Quad8,
        Shape::Tet4,
        Shape::Tet10,
        Shape::Hexa8,
        Shape::Hexa20,
        Shape::Wedge6,
    ];

    #[test]
    fn shape_functions_sum_to_one_and_derivatives_to_zero() {
        for s in ALL {
            let mut n = [0.0; 20];
            let mut dn = [[0.0; 3]; 20];
            s.eval([0.21, 0.33, -0.4], &mut n, &mut dn);
            let m = s.n_nodes();
            assert!((n[..m].iter().sum::<f64>() - 1.0).abs() < 1e-14, "{s:?}");
            for k in 0..3 {
                assert!(
                    dn[..m].iter().map(|d| d[k]).sum::<f64>().abs() < 1e-14,
                    "{s:?}"
                );
            }
        }
    }

    #[test]
    fn shape_derivatives_match_finite_differences() {
        for s in ALL {
            let xi = [0.17, 0.23, 0.31];
            let (mut n0, mut n1, mut dn) = ([0.0; 20], [0.0; 20], [[0.0; 3]; 20]);
            s.eval(xi, &mut n0, &mut dn);
            let h = 1e-6;
            for k in 0..s.dim() {
                let (mut xp, mut xm) = (xi, xi);
                xp[k] += h;
                xm[k] -= h;
                let mut d = [[0.0; 3]; 20];
                s.eval(xp, &mut n1, &mut d);
                let mut nm = [0.0; 20];
                s.eval(xm, &mut nm, &mut d);
                for a in 0..s.n_nodes() {
                    let fd = (n1[a] - nm[a]) / (2.0 * h);
                    assert!((fd - dn[a][k]).abs() < 1e-8, "{s:?} node {a} dir {k}");
                }
            }
        }
    }

    #[test]
    fn quad_nodes_are_kronecker() {
        for (a, p) in QUAD8_NODES.iter().enumerate() {
            let (mut n, mut dn) = ([0.0; 10], [[0.0; 3]; 10]);
            Shape::Quad8.eval([p[0], p[1], 0.0], &mut n, &mut dn);
            for (b, v) in n.iter().enumerate() {
                assert!((v - if a == b { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
    }

    /// The 6-node triangle: N_a(node b) = δ_ab at its corners and mid-sides (OOFEM's order),
    /// and it reproduces quadratic fields: Σ N_a·f(ξ_a) = f for f = ξ², ξη, η².
    #[test]
    fn tri6_is_kronecker_and_quadratically_complete() {
        let nodes = [
            [1.0, 0.0],
            [0.0, 1.0],
            [0.0, 0.0],
            [0.5, 0.5],
            [0.0, 0.5],
            [0.5, 0.0],
        ];
        let (mut n, mut dn) = ([0.0; 6], [[0.0; 3]; 6]);
        for (a, p) in nodes.iter().enumerate() {
            Shape::Tri6.eval([p[0], p[1], 0.0], &mut n, &mut dn);
            for (b, v) in n.iter().enumerate() {
                assert!((v - if a == b { 1.0 } else { 0.0 }).abs() < 1e-14);
            }
        }
        let fields: [fn(f64, f64) -> f64; 3] = [|x, _| x * x, |x, y| x * y, |_, y| y * y];
        let (x, y) = (0.21, 0.37);
        Shape::Tri6.eval([x, y, 0.0], &mut n, &mut dn);
        for f in fields {
            let v: f64 = nodes.iter().zip(n).map(|(p, na)| na * f(p[0], p[1])).sum();
            assert!((v - f(x, y)).abs() < 1e-14);
        }
    }

    /// The 10-node tetrahedron: N_a(node b) = δ_ab at its corners and mid-edges (OOFEM's order:
    /// 5 on 1–2, 6 on 2–3, 7 on 3–1, 8 on 1–4, 9 on 2–4, 10 on 3–4), it reproduces every
    /// quadratic field, and each face's six nodes are the Tri6 of that face (the mid-sides of
    /// its sides 1–2, 2–3, 3–1 in that order).
    #[test]
    fn tet10_is_kronecker_quadratically_complete_and_its_faces_are_tri6() {
        let corners = [
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, 0.0],
        ];
        let mid = |a: usize, b: usize| -> [f64; 3] {
            std::array::from_fn(|k| 0.5 * (corners[a][k] + corners[b][k]))
        };
        let mut nodes = corners.to_vec();
        nodes.extend([
            mid(0, 1),
            mid(1, 2),
            mid(2, 0),
            mid(0, 3),
            mid(1, 3),
            mid(2, 3),
        ]);
        let (mut n, mut dn) = ([0.0; 10], [[0.0; 3]; 10]);
        for (a, p) in nodes.iter().enumerate() {
            Shape::Tet10.eval(*p, &mut n, &mut dn);
            for (b, v) in n.iter().enumerate() {
                assert!(
                    (v - if a == b { 1.0 } else { 0.0 }).abs() < 1e-14,
                    "{a} {b}"
                );
            }
        }
        let x = [0.21, 0.17, 0.33];
        Shape::Tet10.eval(x, &mut n, &mut dn);
        for i in 0..3 {
            for j in i..3 {
                let v: f64 = nodes.iter().zip(n).map(|(p, na)| na * p[i] * p[j]).sum();
                assert!((v - x[i] * x[j]).abs() < 1e-14);
            }
        }
        for face in Shape::Tet10.boundaries() {
            for k in 0..3 {
                let (a, b) = (face[k], face[(k + 1) % 3]);
                let m = mid(a, b);
                let at = nodes.iter().position(|p| *p == m).unwrap();
                assert_eq!(face[3 + k], at, "face {face:?} side {k}");
            }
        }
    }

    /// The 20-node brick: N_a(node b) = δ_ab at its corners and mid-edges (OOFEM's QSpace order),
    /// it reproduces the quadratic fields of the serendipity space (all of degree ≤ 2), and each
    /// face's eight nodes are the Quad8 of that face.
    #[test]
    fn hexa20_is_kronecker_quadratically_complete_and_its_faces_are_quad8() {
        // OOFEM's FEI3dHexaQuad: nodes 9–12 at (−1, 0, 1), (0, 1, 1), (1, 0, 1), (0, −1, 1),
        // 13–16 the same at ζ = −1, 17–20 at (−1, −1, 0), (−1, 1, 0), (1, 1, 0), (1, −1, 0).
        let mut nodes: Vec<[f64; 3]> = HEXA8_NODES.to_vec();
        for z in [1.0, -1.0] {
            nodes.extend([[-1.0, 0.0, z], [0.0, 1.0, z], [1.0, 0.0, z], [0.0, -1.0, z]]);
        }
        nodes.extend([
            [-1.0, -1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, -1.0, 0.0],
        ]);
        let (mut n, mut dn) = ([0.0; 20], [[0.0; 3]; 20]);
        for (a, p) in nodes.iter().enumerate() {
            Shape::Hexa20.eval(*p, &mut n, &mut dn);
            for (b, v) in n.iter().enumerate() {
                assert!(
                    (v - if a == b { 1.0 } else { 0.0 }).abs() < 1e-14,
                    "{a} {b}"
                );
            }
        }
        let x = [0.21, -0.47, 0.33];
        Shape::Hexa20.eval(x, &mut n, &mut dn);
        for i in 0..3 {
            for j in i..3 {
                let v: f64 = nodes.iter().zip(n).map(|(p, na)| na * p[i] * p[j]).sum();
                assert!((v - x[i] * x[j]).abs() < 1e-14);
            }
        }
        for face in Shape::Hexa20.boundaries() {
            for k in 0..4 {
                let (a, b) = (face[k], face[(k + 1) % 4]);
                let m: [f64; 3] = std::array::from_fn(|c| 0.5 * (nodes[a][c] + nodes[b][c]));
                let at = nodes.iter().position(|p| *p == m).unwrap();
                assert_eq!(face[4 + k], at, "face {face:?} side {k}");
            }
        }
        // The mirror is the same element: node a of the mirror sits where node mirror[a] does
        // in the mirrored (ζ → −ζ) cube.
        for (a, &b) in Shape::Hexa20.mirror().iter().enumerate() {
            let p = nodes[b];
            assert_eq!(nodes[a], [p[0], p[1], -p[2]], "mirror {a}");
        }
    }
}
