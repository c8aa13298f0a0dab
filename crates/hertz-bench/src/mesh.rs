//! A small builder of OOFEM input text for generated problems: structured blocks of 2D quads
//! (linear or quadratic) or bricks, graded coordinates, and the records around them.

use hertz::fem::shape::Shape;
use std::fmt::Write as _;

/// Element kinds the builder makes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Quad1PlaneStrain.
    Q4,
    /// QPlaneStress2d (the domain must be 2dPlaneStress).
    Q8,
    /// LSpace.
    Hex,
}

/// 3D element kinds of [`Input::solid3d`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Solid {
    /// LSpace.
    Hex,
    /// LTRSpace.
    Tet,
    /// LWedge.
    Wedge,
}

impl Solid {
    /// The record name, the shape, and the elements of the unit cell as corner lists (node
    /// order of the element).
    fn reference_cells(self) -> (&'static str, Shape, Vec<Vec<[usize; 3]>>) {
        use hertz::fem::shape::HEXA8_CORNERS;
        match self {
            Solid::Hex => ("LSpace", Shape::Hexa8, vec![HEXA8_CORNERS.to_vec()]),
            Solid::Tet => {
                let perms = [
                    [0, 1, 2],
                    [0, 2, 1],
                    [1, 0, 2],
                    [1, 2, 0],
                    [2, 0, 1],
                    [2, 1, 0],
                ];
                let cells = perms
                    .iter()
                    .map(|p| {
                        let mut c = [0usize; 3];
                        let mut out = vec![c];
                        for &axis in p {
                            c[axis] = 1;
                            out.push(c);
                        }
                        out
                    })
                    .collect();
                ("LTRSpace", Shape::Tet4, cells)
            }
            Solid::Wedge => {
                let tri = [[[0, 0], [1, 0], [1, 1]], [[0, 0], [1, 1], [0, 1]]];
                let cells = tri
                    .iter()
                    .map(|t| {
                        let bottom = t.iter().map(|p| [p[0], p[1], 0]);
                        let top = t.iter().map(|p| [p[0], p[1], 1]);
                        bottom.chain(top).collect()
                    })
                    .collect();
                ("LWedge", Shape::Wedge6, cells)
            }
        }
    }
}

/// Symmetry `sym` (0..48) of the unit cube applied to corner `c`: the axes permuted by the
/// permutation `sym / 8` and reflected where bit i of `sym % 8` is set. Odd numbers of
/// reflections reverse the handedness of the node order.
pub fn cube_symmetry(sym: usize, c: [usize; 3]) -> [usize; 3] {
    const PERMS: [[usize; 3]; 6] = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [2, 1, 0],
        [1, 0, 2],
    ];
    let p = PERMS[(sym / 8) % 6];
    let mut out = [0; 3];
    for i in 0..3 {
        let v = c[p[i]];
        out[i] = if (sym >> i) & 1 == 1 { 1 - v } else { v };
    }
    out
}

/// The boundary number (1-based) of an LSpace numbered by cube symmetry `sym` that lies on the
/// z = 1 side of its cell (`top`) or the z = 0 side.
pub fn hex_face_on(sym: usize, top: bool) -> usize {
    use hertz::fem::shape::HEXA8_CORNERS;
    let z = usize::from(top);
    Shape::Hexa8
        .boundaries()
        .iter()
        .position(|f| {
            f.iter()
                .all(|&a| cube_symmetry(sym, HEXA8_CORNERS[a])[2] == z)
        })
        .expect("a cube face lies on each side")
        + 1
}

/// A structured block: its node ids by side and the element boundaries on its top and bottom.
#[derive(Debug, Clone, Default)]
pub struct Block {
    /// Node ids along the top (2D: y = max, left to right; 3D: z = max, row-major in x then y).
    pub top: Vec<usize>,
    pub bottom: Vec<usize>,
    /// (element, boundary) on the top and on the bottom.
    pub top_edges: Vec<(usize, usize)>,
    pub bottom_edges: Vec<(usize, usize)>,
    /// First and last element id.
    pub elements: (usize, usize),
    /// First and last node id (3D blocks).
    pub nodes: (usize, usize),
    /// Node ids of the x = min side.
    pub left: Vec<usize>,
}

/// Input text under construction.
#[derive(Debug, Clone, Default)]
pub struct Input {
    pub nodes: Vec<[f64; 3]>,
    pub elements: Vec<String>,
    pub segments: Vec<String>,
    pub sections: Vec<String>,
    pub materials: Vec<String>,
    pub bcs: Vec<String>,
    pub functions: Vec<String>,
    pub sets: Vec<String>,
    /// Shape and node ids of the elements made by the block builders, in element order.
    pub cells: Vec<(Shape, Vec<usize>)>,
}

/// Coordinates 0..length: spacing h up to `fine`, then growing by `growth` per element.
pub fn graded(length: f64, h: f64, fine: f64, growth: f64) -> Vec<f64> {
    let mut xs = vec![0.0];
    while *xs.last().expect("non-empty") < fine - 1e-12 {
        let x = (xs.last().expect("non-empty") + h).min(fine);
        xs.push(x);
    }
    let mut step = h;
    while *xs.last().expect("non-empty") < length - 1e-12 {
        step *= growth;
        let last = *xs.last().expect("non-empty");
        let mut next = last + step;
        if length - next < step {
            next = length;
        }
        xs.push(next.min(length));
    }
    xs
}

/// `n` equal intervals from a to b.
pub fn uniform(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

impl Input {
    pub fn node(&mut self, x: f64, y: f64, z: f64) -> usize {
        self.nodes.push([x, y, z]);
        self.nodes.len()
    }

    /// A 2D block over the column coordinates `xs`, with the y coordinates of column i given by
    /// `ys(i)` (bottom to top). OOFEM's quad order: (x1,y1), (x0,y1), (x0,y0), (x1,y0); edge 1 is
    /// the top, edge 3 the bottom.
    pub fn block2d(
        &mut self,
        kind: Kind,
        xs: &[f64],
        ys: &dyn Fn(usize) -> Vec<f64>,
        extra: &str,
    ) -> Block {
        let q8 = kind == Kind::Q8;
        let first = self.elements.len() + 1;
        let mut b = Block::default();
        if !q8 {
            let ids: Vec<Vec<usize>> = xs
                .iter()
                .enumerate()
                .map(|(i, &x)| ys(i).iter().map(|&y| self.node(x, y, 0.0)).collect())
                .collect();
            for i in 0..xs.len() - 1 {
                let ny = ids[i].len() - 1;
                for j in 0..ny {
                    let n = [ids[i + 1][j + 1], ids[i][j + 1], ids[i][j], ids[i + 1][j]];
                    self.elements.push(format!(
                        "Quad1PlaneStrain {} nodes 4 {} {} {} {} {extra}",
                        self.elements.len() + 1,
                        n[0],
                        n[1],
                        n[2],
                        n[3]
                    ));
                    self.cells.push((Shape::Quad4, n.to_vec()));
                    let e = self.elements.len();
                    if j + 1 == ny {
                        b.top_edges.push((e, 1));
                    }
                    if j == 0 {
                        b.bottom_edges.push((e, 3));
                    }
                }
            }
            b.top = ids.iter().map(|c| *c.last().expect("column")).collect();
            b.bottom = ids.iter().map(|c| c[0]).collect();
            b.left = ids[0].clone();
        } else {
            // Corner grid plus mid-side nodes; columns 2i are corners, 2i+1 mid columns.
            let nx = xs.len() - 1;
            let ny = ys(0).len() - 1;
            let mut grid = vec![vec![0usize; 2 * ny + 1]; 2 * nx + 1];
            for ci in 0..=2 * nx {
                for cj in 0..=2 * ny {
                    if ci % 2 == 1 && cj % 2 == 1 {
                        continue;
                    }
                    let (i0, i1) = (ci / 2, ci.div_ceil(2));
                    let x = 0.5 * (xs[i0] + xs[i1]);
                    let y_at = |i: usize| {
                        let c = ys(i);
                        0.5 * (c[cj / 2] + c[cj.div_ceil(2)])
                    };
                    let y = 0.5 * (y_at(i0) + y_at(i1));
                    grid[ci][cj] = self.node(x, y, 0.0);
                }
            }
            for i in 0..nx {
                for j in 0..ny {
                    let (ci, cj) = (2 * i, 2 * j);
                    let n = [
                        grid[ci + 2][cj + 2],
                        grid[ci][cj + 2],
                        grid[ci][cj],
                        grid[ci + 2][cj],
                        grid[ci + 1][cj + 2],
                        grid[ci][cj + 1],
                        grid[ci + 1][cj],
                        grid[ci + 2][cj + 1],
                    ];
                    let list: Vec<String> = n.iter().map(|v| v.to_string()).collect();
                    self.elements.push(format!(
                        "QPlaneStress2d {} nodes 8 {} {extra}",
                        self.elements.len() + 1,
                        list.join(" ")
                    ));
                    self.cells.push((Shape::Quad8, n.to_vec()));
                    let e = self.elements.len();
                    if j + 1 == ny {
                        b.top_edges.push((e, 1));
                    }
                    if j == 0 {
                        b.bottom_edges.push((e, 3));
                    }
                }
            }
            b.top = (0..=2 * nx).map(|ci| grid[ci][2 * ny]).collect();
            b.bottom = (0..=2 * nx).map(|ci| grid[ci][0]).collect();
            b.left = (0..=2 * ny).map(|cj| grid[0][cj]).collect();
        }
        b.elements = (first, self.elements.len());
        b
    }

    /// A brick block of LSpace elements over the coordinates `x`, `y`, `z` (z is up: `top` and
    /// `bottom` are the z = max and z = min layers, row-major in x then y; `left` is x = min).
    pub fn block3d(&mut self, x: &[f64], y: &[f64], z: &[f64], extra: &str) -> Block {
        self.solid3d(Solid::Hex, x, y, z, extra, 0)
    }

    /// A block of 3D elements over the grid `x`, `y`, `z` (sides as [`Input::block3d`]): each
    /// grid cell becomes one LSpace, six LTRSpace (the Kuhn split along a main diagonal) or two
    /// LWedge (split by a diagonal plane), laid out in a reference cell that the cube symmetry
    /// `sym` (0..48, see [`cube_symmetry`]) maps onto the grid cell. Varying `sym` changes which
    /// element face numbers lie on the block's sides, the node order's handedness, and for
    /// wedges the extrusion axis.
    pub fn solid3d(
        &mut self,
        kind: Solid,
        x: &[f64],
        y: &[f64],
        z: &[f64],
        extra: &str,
        sym: usize,
    ) -> Block {
        let first = self.elements.len() + 1;
        let first_node = self.nodes.len() + 1;
        let (nx, ny, nz) = (x.len() - 1, y.len() - 1, z.len() - 1);
        let mut id = vec![vec![vec![0usize; nz + 1]; ny + 1]; nx + 1];
        for (k, &zk) in z.iter().enumerate() {
            for (j, &yj) in y.iter().enumerate() {
                for (i, &xi) in x.iter().enumerate() {
                    id[i][j][k] = self.node(xi, yj, zk);
                }
            }
        }
        let (name, shape, cells) = kind.reference_cells();
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    for cell in &cells {
                        let nodes: Vec<usize> = cell
                            .iter()
                            .map(|&c| {
                                let g = cube_symmetry(sym, c);
                                id[i + g[0]][j + g[1]][k + g[2]]
                            })
                            .collect();
                        let list: Vec<String> = nodes.iter().map(|v| v.to_string()).collect();
                        self.elements.push(format!(
                            "{name} {} nodes {} {} {extra}",
                            self.elements.len() + 1,
                            nodes.len(),
                            list.join(" ")
                        ));
                        self.cells.push((shape, nodes));
                    }
                }
            }
        }
        let mut b = Block::default();
        for j in 0..=ny {
            for i in 0..=nx {
                b.top.push(id[i][j][nz]);
                b.bottom.push(id[i][j][0]);
            }
        }
        for k in 0..=nz {
            for j in 0..=ny {
                b.left.push(id[0][j][k]);
            }
        }
        b.elements = (first, self.elements.len());
        b.nodes = (first_node, self.nodes.len());
        b
    }

    /// Turn the linear tetrahedra and bricks among elements `first..=last` (ids) into OOFEM's
    /// quadratic ones (LTRSpace → QTRSpace, LSpace → QSpace): a node in the middle of each edge,
    /// shared by the elements around it, in the order of the linear shape's `edges()`. Returns
    /// the new nodes' ids (the caller may move them off the chords).
    pub fn make_quadratic(&mut self, (first, last): (usize, usize)) -> Vec<usize> {
        let mut mids: std::collections::HashMap<(usize, usize), usize> = Default::default();
        let mut added = Vec::new();
        for e in first..=last {
            let (shape, nodes) = self.cells[e - 1].clone();
            let (quadratic, name) = match shape {
                Shape::Tet4 => (Shape::Tet10, "QTRSpace"),
                Shape::Hexa8 => (Shape::Hexa20, "QSpace"),
                _ => continue,
            };
            let mut all = nodes.clone();
            for edge in shape.edges() {
                let (a, b) = (nodes[edge[0]], nodes[edge[1]]);
                let id = *mids.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (p, q) = (self.nodes[a - 1], self.nodes[b - 1]);
                    self.nodes
                        .push(std::array::from_fn(|i| 0.5 * (p[i] + q[i])));
                    added.push(self.nodes.len());
                    self.nodes.len()
                });
                all.push(id);
            }
            let words: Vec<&str> = self.elements[e - 1].split_whitespace().collect();
            let rest = words[4 + nodes.len()..].join(" ");
            let list: Vec<String> = all.iter().map(|v| v.to_string()).collect();
            self.elements[e - 1] = format!(
                "{name} {} nodes {} {} {rest}",
                words[1],
                all.len(),
                list.join(" ")
            );
            self.cells[e - 1] = (quadratic, all);
        }
        added
    }

    /// The boundaries (element, boundary number) of the 3D elements of `block` whose nodes all
    /// satisfy `on`: the faces of a side picked by position, whatever the elements' node order.
    pub fn faces_where(&self, block: &Block, on: &dyn Fn([f64; 3]) -> bool) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (e, (shape, nodes)) in self.cells.iter().enumerate() {
            if shape.dim() != 3 || e + 1 < block.elements.0 || e + 1 > block.elements.1 {
                continue;
            }
            for (b, local) in shape.boundaries().iter().enumerate() {
                if local.iter().all(|&a| on(self.nodes[nodes[a] - 1])) {
                    out.push((e + 1, b + 1));
                }
            }
        }
        out
    }

    /// The nodes (ids) whose coordinates satisfy `on`.
    pub fn nodes_where(&self, on: &dyn Fn([f64; 3]) -> bool) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&i| on(self.nodes[i]))
            .map(|i| i + 1)
            .collect()
    }

    /// Add a set record; returns its number.
    pub fn set(&mut self, body: String) -> usize {
        let k = self.sets.len() + 1;
        self.sets.push(format!("Set {k} {body}"));
        k
    }

    pub fn node_set(&mut self, ids: &[usize]) -> usize {
        let list: Vec<String> = ids.iter().map(|v| v.to_string()).collect();
        self.set(format!("nodes {} {}", ids.len(), list.join(" ")))
    }

    pub fn boundary_set(&mut self, edges: &[(usize, usize)]) -> usize {
        let list: Vec<String> = edges.iter().map(|(e, b)| format!("{e} {b}")).collect();
        self.set(format!(
            "elementboundaries {} {}",
            2 * edges.len(),
            list.join(" ")
        ))
    }

    /// The whole input file.
    pub fn render(&self, title: &str, analysis: &str, domain: &str) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{title}.out\n{title}\n{analysis}\ndomain {domain}\nOutputManager"
        );
        let _ = writeln!(
            s,
            "ndofman {} nelem {} ncrosssect {} nmat {} nbc {} nic 0 nltf {} nset {} ncontactseg {}",
            self.nodes.len(),
            self.elements.len(),
            self.sections.len(),
            self.materials.len(),
            self.bcs.len(),
            self.functions.len(),
            self.sets.len(),
            self.segments.len()
        );
        let three = domain == "3d";
        for (k, x) in self.nodes.iter().enumerate() {
            if three {
                let _ = writeln!(
                    s,
                    "node {} coords 3 {:.12} {:.12} {:.12}",
                    k + 1,
                    x[0],
                    x[1],
                    x[2]
                );
            } else {
                let _ = writeln!(s, "node {} coords 2 {:.12} {:.12}", k + 1, x[0], x[1]);
            }
        }
        for part in [
            &self.elements,
            &self.segments,
            &self.sections,
            &self.materials,
            &self.bcs,
            &self.functions,
            &self.sets,
        ] {
            for line in part {
                s.push_str(line);
                s.push('\n');
            }
        }
        s
    }
}
