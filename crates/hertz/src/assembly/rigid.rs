//! The rigid-body motions that supports and ties leave free: a body held by contact alone.
//!
//! Read from the model's structure, not from a factorization: a body that floats makes the
//! structural tangent singular in exact arithmetic, but the round-off pivot of its free motion
//! grows with the body (a 25 000-node tetrahedral hemisphere passed the pivot test of
//! [`crate::solve::linear`] as regular, and its first contact step moved it by 10¹⁰).
//!
//! The bodies are the nodes joined by elements and by `SlaveNode` ties. A body's rigid motions
//! are translations and rotations (in the plane, the in-plane ones; in axisymmetry the axial
//! translation alone), each restricted to the DOFs its nodes have; a motion is restrained where
//! it moves a prescribed DOF or breaks a tie (a slave node not moving as its masters' weighted
//! sum). The free ones are the motions left, counted by the rank of small Gram matrices.

use super::DofMap;
use crate::model::{DomainKind, Model};
use faer::Mat;

/// Relative size below which an eigenvalue of a Gram matrix counts as zero: motions and
/// constraints are scaled to the body's size, so a motion restrained at points 10⁻⁴ of the
/// body's size from its axis still shows as 10⁻⁸ of the largest.
const RANK_TOL: f64 = 1e-12;

/// The number of independent rigid-body motions of the model's bodies that no prescribed DOF
/// and no tie restrains (0: every body is supported on its own).
pub fn free_rigid_motions(model: &Model, dofs: &DofMap) -> usize {
    let nn = model.nodes.len();
    let mut parent: Vec<usize> = (0..nn).collect();
    let mut in_body = vec![false; nn];
    for el in &model.elements {
        for &n in &el.nodes {
            in_body[n] = true;
            union(&mut parent, el.nodes[0], n);
        }
    }
    for (n, node) in model.nodes.iter().enumerate() {
        if let Some(s) = node.slave.as_ref().filter(|_| in_body[n]) {
            for &m in &s.masters {
                in_body[m] = true;
                union(&mut parent, n, m);
            }
        }
    }
    let axisymmetric = model.elements.iter().any(|e| e.etype.is_axisymmetric());
    let mut bodies: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for n in (0..nn).filter(|&n| in_body[n]) {
        bodies.entry(find(&mut parent, n)).or_default().push(n);
    }
    let prescribed: std::collections::HashSet<(usize, u8)> =
        dofs.prescribed.iter().map(|&(n, d, _)| (n, d)).collect();
    bodies
        .values()
        .map(|nodes| body_free_motions(model, dofs, nodes, &prescribed, axisymmetric))
        .sum()
}

/// The free rigid motions of one body (`nodes`, ties' masters among them).
fn body_free_motions(
    model: &Model,
    dofs: &DofMap,
    nodes: &[usize],
    prescribed: &std::collections::HashSet<(usize, u8)>,
    axisymmetric: bool,
) -> usize {
    let x = |n: usize| model.nodes[n].coords;
    let mut centre = [0.0; 3];
    for &n in nodes {
        for k in 0..3 {
            centre[k] += x(n)[k] / nodes.len() as f64;
        }
    }
    let size = nodes
        .iter()
        .flat_map(|&n| (0..3).map(move |k| (x(n)[k] - centre[k]).abs()))
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let motions = motions(model.domain, axisymmetric);
    // The value of every motion at DOF `d` (1-based) of node `n`.
    let at = |n: usize, d: u8| -> Vec<f64> {
        let p: [f64; 3] = std::array::from_fn(|k| (x(n)[k] - centre[k]) / size);
        motions.iter().map(|m| m(p)[d as usize - 1]).collect()
    };
    let nm = motions.len();
    let mut gram = Mat::<f64>::zeros(nm, nm);
    let mut cons = Mat::<f64>::zeros(nm, nm);
    let add = |g: &mut Mat<f64>, row: &[f64]| {
        for i in 0..nm {
            for j in 0..nm {
                g[(i, j)] += row[i] * row[j];
            }
        }
    };
    for &n in nodes {
        for &(d, _) in &dofs.node_dofs[n] {
            let v = at(n, d);
            add(&mut gram, &v);
            if prescribed.contains(&(n, d)) {
                add(&mut cons, &v);
            }
            if let Some(s) = &model.nodes[n].slave {
                // The tie: this node's motion minus its masters' weighted sum.
                let mut row = v.clone();
                for (&m, &w) in s.masters.iter().zip(&s.weights) {
                    for (r, vm) in row.iter_mut().zip(at(m, d)) {
                        *r -= w * vm;
                    }
                }
                add(&mut cons, &row);
            }
        }
    }
    // The motions no constraint sees, then how many of them move the body's DOFs at all.
    let free = null_space(&cons);
    if free.ncols() == 0 {
        return 0;
    }
    let reduced = free.transpose() * &gram * &free;
    rank(&reduced)
}

/// A rigid motion's displacement at a point (coordinates about the body's centre, scaled).
type Motion = fn([f64; 3]) -> [f64; 3];

/// The rigid motions of a domain's bodies: translations and rotations; in axisymmetry the
/// axial translation alone (a radial one strains the hoop).
fn motions(domain: DomainKind, axisymmetric: bool) -> Vec<Motion> {
    let tx: Motion = |_| [1.0, 0.0, 0.0];
    let ty: Motion = |_| [0.0, 1.0, 0.0];
    let tz: Motion = |_| [0.0, 0.0, 1.0];
    let rx: Motion = |p| [0.0, -p[2], p[1]];
    let ry: Motion = |p| [p[2], 0.0, -p[0]];
    let rz: Motion = |p| [-p[1], p[0], 0.0];
    if axisymmetric {
        return vec![ty];
    }
    match domain {
        DomainKind::PlaneStress | DomainKind::PlaneStrain => vec![tx, ty, rz],
        // Trusses and solids: every motion, restricted to the DOFs the nodes have.
        _ => vec![tx, ty, tz, rx, ry, rz],
    }
}

/// An orthonormal basis of the null space of the symmetric positive semi-definite `g`.
fn null_space(g: &Mat<f64>) -> Mat<f64> {
    let eig = g
        .self_adjoint_eigen(faer::Side::Lower)
        .expect("a small symmetric matrix");
    let (s, u) = (eig.S(), eig.U());
    let n = g.nrows();
    let largest = (0..n).map(|i| s[i].abs()).fold(0.0f64, f64::max);
    let cols: Vec<usize> = (0..n)
        .filter(|&i| s[i].abs() <= RANK_TOL * largest.max(1.0))
        .collect();
    Mat::from_fn(n, cols.len(), |i, j| u[(i, cols[j])])
}

/// The numerical rank of the symmetric positive semi-definite `g`.
fn rank(g: &Mat<f64>) -> usize {
    let n = g.nrows();
    n - null_space(g).ncols()
}

fn find(parent: &mut [usize], mut a: usize) -> usize {
    while parent[a] != a {
        parent[a] = parent[parent[a]];
        a = parent[a];
    }
    a
}

fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra] = rb;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The free rigid motions of a model: `nodes` (records), `elements` (records, section and
    /// material 1), the Dirichlet conditions `bcs` (records on sets 2…), the node sets `sets`.
    fn free(domain: &str, nodes: &str, elements: &str, bcs: &[&str], sets: &[&str]) -> usize {
        let set_records: Vec<String> = sets
            .iter()
            .enumerate()
            .map(|(k, s)| format!("Set {} nodes {s}", k + 2))
            .collect();
        let text = format!(
            "m.out\nrigid\nLinearStatic nsteps 1\ndomain {domain}\nOutputManager\n\
             ndofman {} nelem {} ncrosssect 1 nmat 1 nbc {} nic 0 nltf 1 nset {}\n{nodes}\n\
             {elements}\nSimpleCS 1 thick 1 material 1 set 1\nIsoLE 1 d 1 E 1 n 0.3 tAlpha 0\n\
             {}\nConstantFunction 1 f(t) 1\nSet 1 allelements\n{}\n",
            nodes.lines().count(),
            elements.lines().count(),
            bcs.len(),
            sets.len() + 1,
            bcs.join("\n"),
            set_records.join("\n"),
        );
        let model = crate::input::read_model_str(&text, "m.in").unwrap().model;
        let dofs = DofMap::new(&model, &Default::default()).unwrap();
        free_rigid_motions(&model, &dofs)
    }

    const SQUARE: &str = "node 1 coords 2 0 0\nnode 2 coords 2 1 0\nnode 3 coords 2 1 1\n\
                          node 4 coords 2 0 1";
    const QUAD: &str = "PlaneStress2d 1 nodes 4 1 2 3 4";

    fn bc(number: usize, dofs: &str, set: usize) -> String {
        let n = dofs.split_whitespace().count();
        let zeros = vec!["0"; n].join(" ");
        format!(
            "BoundaryCondition {number} loadTimeFunction 1 dofs {n} {dofs} values {n} {zeros} \
             set {set}"
        )
    }

    /// A plane square: free (3), pinned at a corner (the rotation), on rollers along its base
    /// (the sliding), pinned and on a roller (none), on two rollers in one line (the sliding
    /// along it).
    #[test]
    fn a_plane_body_keeps_the_motions_its_supports_leave() {
        assert_eq!(free("2dPlaneStress", SQUARE, QUAD, &[], &[]), 3);
        assert_eq!(
            free("2dPlaneStress", SQUARE, QUAD, &[&bc(1, "1 2", 2)], &["1 1"]),
            1
        );
        assert_eq!(
            free("2dPlaneStress", SQUARE, QUAD, &[&bc(1, "2", 2)], &["2 1 2"]),
            1
        );
        let pinned_and_roller = [bc(1, "1 2", 2), bc(2, "2", 3)];
        let refs: Vec<&str> = pinned_and_roller.iter().map(String::as_str).collect();
        assert_eq!(
            free("2dPlaneStress", SQUARE, QUAD, &refs, &["1 1", "1 2"]),
            0
        );
        assert_eq!(
            free("2dPlaneStress", SQUARE, QUAD, &[&bc(1, "1", 2)], &["2 1 4"]),
            1
        );
    }

    /// Two squares side by side, not joined: one held, the other free (its 3 motions); joined
    /// through a shared node they are one body, held.
    #[test]
    fn bodies_are_the_nodes_elements_join() {
        let nodes = format!(
            "{SQUARE}\nnode 5 coords 2 2 0\nnode 6 coords 2 3 0\nnode 7 coords 2 3 1\n\
             node 8 coords 2 2 1"
        );
        let apart = format!("{QUAD}\nPlaneStress2d 2 nodes 4 5 6 7 8");
        let fixed = bc(1, "1 2", 2);
        assert_eq!(
            free("2dPlaneStress", &nodes, &apart, &[&fixed], &["2 1 2"]),
            3
        );
        let joined = format!("{QUAD}\nPlaneStress2d 2 nodes 4 2 6 7 3");
        assert_eq!(
            free("2dPlaneStress", &nodes, &joined, &[&fixed], &["2 1 2"]),
            0
        );
    }

    /// A square whose top nodes are `SlaveNode`s of a master node (no element of its own) held
    /// sideways: the ties stop the rotation, the support the sliding; the vertical translation
    /// is free (a body held by contact alone, as in the two hemispheres of BENCHMARKS.md). With
    /// the master held both ways, nothing is free.
    #[test]
    fn ties_join_bodies_and_restrain_what_they_break() {
        let nodes = "node 1 coords 2 0 0\nnode 2 coords 2 1 0\n\
                     SlaveNode 3 coords 2 1 1 masterDofMan 1 5 doftype 2 2 2\n\
                     SlaveNode 4 coords 2 0 1 masterDofMan 1 5 doftype 2 2 2\n\
                     node 5 coords 2 0.5 2";
        assert_eq!(
            free("2dPlaneStress", nodes, QUAD, &[&bc(1, "1", 2)], &["1 5"]),
            1
        );
        assert_eq!(
            free("2dPlaneStress", nodes, QUAD, &[&bc(1, "1 2", 2)], &["1 5"]),
            0
        );
    }

    /// A brick: free (6); its base held vertically (the two slidings and the spin about the
    /// vertical stay); its base held every way (none).
    #[test]
    fn a_solid_has_six_motions() {
        let nodes = "node 1 coords 3 0 0 0\nnode 2 coords 3 1 0 0\nnode 3 coords 3 1 1 0\n\
                     node 4 coords 3 0 1 0\nnode 5 coords 3 0 0 1\nnode 6 coords 3 1 0 1\n\
                     node 7 coords 3 1 1 1\nnode 8 coords 3 0 1 1";
        let brick = "LSpace 1 nodes 8 1 2 3 4 5 6 7 8";
        assert_eq!(free("3d", nodes, brick, &[], &[]), 6);
        assert_eq!(
            free("3d", nodes, brick, &[&bc(1, "3", 2)], &["4 1 2 3 4"]),
            3
        );
        assert_eq!(
            free("3d", nodes, brick, &[&bc(1, "1 2 3", 2)], &["4 1 2 3 4"]),
            0
        );
    }

    /// An axisymmetric ring moves rigidly along its axis only (a radial motion strains the
    /// hoop); holding one node axially holds it.
    #[test]
    fn an_axisymmetric_body_slides_along_its_axis_alone() {
        let ring = "node 1 coords 2 1 0\nnode 2 coords 2 2 0\nnode 3 coords 2 2 1\n\
                    node 4 coords 2 1 1";
        let quad = "L4Axisymm 1 nodes 4 1 2 3 4";
        assert_eq!(free("2dPlaneStress", ring, quad, &[], &[]), 1);
        assert_eq!(
            free("2dPlaneStress", ring, quad, &[&bc(1, "2", 2)], &["1 1"]),
            0
        );
    }
}
