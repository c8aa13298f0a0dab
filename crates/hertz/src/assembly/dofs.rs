//! DOF numbering (spec §3.1): each node carries the DOF ids its elements need; DOFs with a
//! Dirichlet condition are prescribed, slave-node DOFs are weighted sums of master DOFs, the rest
//! get equation numbers in node order, DOF-id order.
//!
//! Primary index space: free equations `0..n_free`, then prescribed DOFs `n_free..n_primary`.
//! A location code `< n_primary` is a primary index; otherwise `code - n_primary` is a slave entry.

use crate::error::{Error, Result};
use crate::model::{DofId, Model};

/// What other parts of the model (contact) need from the numbering beyond the elements' DOFs.
#[derive(Debug, Clone, Default)]
pub struct ExtraDofs {
    /// Nodes that carry the domain's displacement DOFs even without elements (e.g. the reference
    /// node of a rigid indenter).
    pub nodes: Vec<usize>,
    /// Lagrange multipliers, numbered after all displacement equations.
    pub n_multipliers: usize,
}

#[derive(Debug, Clone)]
pub struct DofMap {
    /// Per node: (DOF id, location code), sorted by DOF id.
    pub node_dofs: Vec<Vec<(DofId, usize)>>,
    /// Free equations: displacements, then multipliers.
    pub n_free: usize,
    pub n_prescribed: usize,
    /// DOF id of every primary DOF (0 for multipliers).
    pub primary_dof_id: Vec<DofId>,
    /// Per prescribed DOF: (node, DOF id, Dirichlet index into `model.dirichlet`).
    pub prescribed: Vec<(usize, DofId, usize)>,
    /// Slave entries: (primary index, weight) lists.
    pub slaves: Vec<Vec<(usize, f64)>>,
    /// Lagrange multipliers: the last `n_lambda` free equations.
    pub n_lambda: usize,
}

impl DofMap {
    pub fn new(model: &Model, extra: &ExtraDofs) -> Result<DofMap> {
        let nn = model.nodes.len();
        let mut ids: Vec<u8> = vec![0; nn]; // bit mask of DOF ids 1..3
        for el in &model.elements {
            let mask = el.dof_ids().iter().fold(0u8, |m, &d| m | (1 << d));
            for &n in &el.nodes {
                ids[n] |= mask;
                if let Some(s) = &model.nodes[n].slave {
                    for &m in &s.masters {
                        ids[m] |= mask;
                    }
                }
            }
        }
        let nsd = model.domain.nsd();
        for &n in &extra.nodes {
            for d in 1..=nsd as u8 {
                ids[n] |= 1 << d;
            }
        }
        let n_lambda = extra.n_multipliers;
        // Dirichlet condition per (node, dof): later conditions override earlier ones.
        let mut bc_of: Vec<[Option<usize>; 4]> = vec![[None; 4]; nn];
        for (bi, bc) in model.dirichlet.iter().enumerate() {
            let Some(s) = bc.set else { continue };
            for &n in &model.sets[s - 1].nodes {
                if model.nodes[n].slave.is_some() {
                    continue;
                }
                for &d in &bc.dofs {
                    if ids[n] & (1 << d) != 0 {
                        bc_of[n][d as usize] = Some(bi);
                    }
                }
            }
        }
        let (mut n_free, mut n_prescribed) = (0, 0);
        for n in 0..nn {
            if model.nodes[n].slave.is_some() {
                continue;
            }
            for d in 1..=3u8 {
                if ids[n] & (1 << d) != 0 {
                    if bc_of[n][d as usize].is_some() {
                        n_prescribed += 1;
                    } else {
                        n_free += 1;
                    }
                }
            }
        }
        // Multipliers are free equations after the displacement ones (DOF id 0).
        n_free += n_lambda;
        let n_primary = n_free + n_prescribed;
        let mut node_dofs = vec![Vec::new(); nn];
        let mut primary_dof_id = vec![0; n_primary];
        let mut prescribed = Vec::with_capacity(n_prescribed);
        let (mut f, mut p) = (0, 0);
        for n in 0..nn {
            if model.nodes[n].slave.is_some() {
                continue;
            }
            for d in 1..=3u8 {
                if ids[n] & (1 << d) == 0 {
                    continue;
                }
                let code = match bc_of[n][d as usize] {
                    Some(bi) => {
                        prescribed.push((n, d, bi));
                        p += 1;
                        n_free + p - 1
                    }
                    None => {
                        f += 1;
                        f - 1
                    }
                };
                primary_dof_id[code] = d;
                node_dofs[n].push((d, code));
            }
        }
        let mut slaves = Vec::new();
        for n in 0..nn {
            let Some(s) = &model.nodes[n].slave else {
                continue;
            };
            for d in 1..=3u8 {
                if ids[n] & (1 << d) == 0 {
                    continue;
                }
                let mut entries = Vec::new();
                for (&m, &w) in s.masters.iter().zip(&s.weights) {
                    let code = node_dofs[m]
                        .iter()
                        .find(|(id, _)| *id == d)
                        .map(|x| x.1)
                        .ok_or_else(|| Error::Input {
                            span: model.nodes[n].span.clone(),
                            msg: format!(
                                "master node {} has no DOF {d} for slave node",
                                model.nodes[m].label
                            ),
                        })?;
                    entries.push((code, w));
                }
                node_dofs[n].push((d, n_primary + slaves.len()));
                slaves.push(entries);
            }
        }
        Ok(DofMap {
            node_dofs,
            n_free,
            n_prescribed,
            primary_dof_id,
            prescribed,
            slaves,
            n_lambda,
        })
    }

    /// Node of every free equation (for node-graph orderings).
    pub fn free_eq_nodes(&self) -> Vec<usize> {
        // Multipliers get groups of their own.
        let nn = self.node_dofs.len();
        let mut g: Vec<usize> = (0..self.n_free).map(|c| nn + c).collect();
        for (n, list) in self.node_dofs.iter().enumerate() {
            for &(_, c) in list {
                if c < self.n_free {
                    g[c] = n;
                }
            }
        }
        g
    }

    pub fn n_primary(&self) -> usize {
        self.n_free + self.n_prescribed
    }

    /// Location code of DOF `d` of node `n`, if the node has it.
    pub fn code(&self, n: usize, d: DofId) -> Option<usize> {
        self.node_dofs[n]
            .iter()
            .find(|(id, _)| *id == d)
            .map(|x| x.1)
    }

    /// Primary (index, weight) entries of a location code.
    pub fn entries(&self, code: usize) -> Entries<'_> {
        if code < self.n_primary() {
            Entries::One(Some((code, 1.0)))
        } else {
            Entries::Many(self.slaves[code - self.n_primary()].iter())
        }
    }

    /// Value of a location code in the primary vector `u`.
    pub fn value(&self, u: &[f64], code: usize) -> f64 {
        self.entries(code).map(|(p, w)| w * u[p]).sum()
    }
}

/// Iterator over the primary (index, weight) pairs of a location code.
pub enum Entries<'a> {
    One(Option<(usize, f64)>),
    Many(std::slice::Iter<'a, (usize, f64)>),
}

impl Iterator for Entries<'_> {
    type Item = (usize, f64);
    fn next(&mut self) -> Option<(usize, f64)> {
        match self {
            Entries::One(x) => x.take(),
            Entries::Many(it) => it.next().copied(),
        }
    }
}
