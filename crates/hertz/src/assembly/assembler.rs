//! Element loop: internal forces, tangent values on a fixed sparse pattern of the free-free block
//! (CSC; the upper triangle when the tangent is symmetric, both triangles when a contribution is
//! not), integration-point states. Element kernels run in parallel chunks; the
//! scatter is serial in element order, so results do not depend on the thread count.

use super::dofs::DofMap;
use super::nodal::NodalState;
use super::Contribution;
use crate::error::{Error, Result};
use crate::fem::{rule, QuadPoint};
use crate::material::{law_of, Law};
use crate::model::Model;
use crate::solid::continuum::{ContinuumKernel, MAX_DOFS, MAX_NODES};
use crate::solid::loads::element_thickness;
use crate::solid::truss::truss_axes;
use crate::solid::{ElementKernel, GpState, TrussKernel};
use rayon::prelude::*;
use std::collections::HashMap;

/// CSC pattern of the free-free stiffness block: its upper triangle when `symmetric`, else both
/// triangles.
#[derive(Debug, Clone)]
pub struct Pattern {
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub symmetric: bool,
}

impl Pattern {
    /// Position of entry (row, col) in the value array (row <= col when symmetric).
    #[inline]
    pub fn position(&self, row: usize, col: usize) -> usize {
        debug_assert!(!self.symmetric || row <= col);
        let (s, e) = (self.col_ptr[col], self.col_ptr[col + 1]);
        s + self.row_idx[s..e]
            .binary_search(&row)
            .expect("entry in pattern")
    }
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Σ_j |K_ij| of every row of the matrix with `values` on this pattern (both triangles
    /// counted where one is stored).
    pub fn abs_row_sums(&self, values: &[f64]) -> Vec<f64> {
        let mut sums = vec![0.0; self.n];
        for col in 0..self.n {
            for i in self.col_ptr[col]..self.col_ptr[col + 1] {
                let row = self.row_idx[i];
                sums[row] += values[i].abs();
                if self.symmetric && row != col {
                    sums[col] += values[i].abs();
                }
            }
        }
        sums
    }
}

/// Per-element data prepared once: location codes, rule and material table indices.
struct ElementInfo {
    loc_start: usize,
    ndof: usize,
    rule: usize,
    law: usize,
    thick: f64,
}

/// The tangent values on a sparse pattern (CSC, one triangle if it is symmetric).
pub struct PatternValues<'a> {
    pub pattern: &'a Pattern,
    pub values: &'a mut [f64],
}

impl PatternValues<'_> {
    /// Whether only entries with row ≤ col are kept (a symmetric pattern's upper triangle).
    fn upper_only(&self) -> bool {
        self.pattern.symmetric
    }

    /// Add `v` to entry (row, col) of the free equations.
    #[inline]
    fn add(&mut self, row: usize, col: usize, v: f64) {
        self.values[self.pattern.position(row, col)] += v;
    }
}

/// Accumulators of one evaluation.
struct Sink<'a> {
    f_int: Vec<f64>,
    k_values: Option<Vec<f64>>,
    k_fp_dup: Option<Vec<f64>>,
    dup: Option<&'a [f64]>,
    ebe: [f64; 4],
}

/// Global quantities from one element loop.
pub struct Evaluation {
    /// Internal forces in primary numbering (free then prescribed).
    pub f_int: Vec<f64>,
    /// Tangent values on the pattern, if requested.
    pub k_values: Option<Vec<f64>>,
    /// K_fp · Δu_p (free rows), if prescribed increments were given.
    pub k_fp_dup: Option<Vec<f64>>,
    /// Element-by-element squared internal-force norms per DOF id (index 1..3).
    pub ebe: [f64; 4],
    /// Integration-point states per element, if requested.
    pub states: Option<Vec<Vec<GpState>>>,
}

pub struct Assembler<'m> {
    pub model: &'m Model,
    pub dofs: &'m DofMap,
    pub pattern: Pattern,
    elems: Vec<ElementInfo>,
    locs: Vec<usize>,
    rules: Vec<Vec<QuadPoint>>,
    /// Material laws per (material, stress mode, nlgeo).
    laws: Vec<Law>,
    /// Free-equation lists of the contact pairs, included in the pattern.
    couplings: Vec<Vec<usize>>,
    /// Small strain and no law with a state: the elements' stiffness is constant.
    constant_stiffness: bool,
    /// Element stiffness values on the current pattern when no element has `nlgeo` (constant).
    linear_k: std::sync::Mutex<Option<Vec<f64>>>,
    /// Where each element's material state starts in `material_state` (one more entry at the
    /// end): its integration points' states in turn.
    state_at: Vec<usize>,
    /// The material state committed with the last converged step (or substep).
    material_state: Vec<f64>,
    /// Per element, whether this process assembles it in [`Assembler::evaluate_share`] (a
    /// distributed solve, see [`crate::solve::partition`]); None: every element.
    share: Option<Vec<bool>>,
    /// The factor on the elements' forces, tangent and K_fp·Δu_p (not on the `extra`
    /// contributions): 1 but where a step adds stiffness-proportional damping
    /// ([`Assembler::set_element_scale`]).
    element_scale: f64,
}

const CHUNK: usize = 2048;
/// Elements per parallel task.
const RUN: usize = 64;

/// Kernel results of a run of consecutive elements.
#[derive(Default)]
struct RunBuffer {
    values: Vec<f64>,
    offsets: Vec<usize>,
    states: Vec<Vec<GpState>>,
}

impl<'m> Assembler<'m> {
    pub fn new(model: &'m Model, dofs: &'m DofMap) -> Result<Assembler<'m>> {
        let mut rule_ids: HashMap<(crate::fem::Shape, usize), usize> = HashMap::new();
        let mut rules = Vec::new();
        let mut law_ids: HashMap<(usize, u8, bool), usize> = HashMap::new();
        let mut laws = Vec::new();
        let mut elems = Vec::with_capacity(model.elements.len());
        let mut locs = Vec::new();
        for (e, el) in model.elements.iter().enumerate() {
            let shape = el.etype.shape();
            let nip = el.nip.unwrap_or(el.etype.default_nip());
            let r = *rule_ids.entry((shape, nip)).or_insert_with(|| {
                rules.push(rule(shape, nip).expect("nip validated by the reader"));
                rules.len() - 1
            });
            let mode = el.etype.mode();
            let k = *law_ids
                .entry((el.material, mode as u8, el.nlgeo))
                .or_insert_with(|| {
                    laws.push(law_of(&model.materials[el.material], mode, el.nlgeo));
                    laws.len() - 1
                });
            let loc_start = locs.len();
            for &n in &el.nodes {
                for &d in el.dof_ids() {
                    locs.push(dofs.code(n, d).expect("node carries its elements' DOFs"));
                }
            }
            let thick = if el.etype.is_truss() {
                model.cross_sections[el.cross_section].area
            } else if shape.dim() == 2 {
                element_thickness(model, e)
            } else {
                1.0
            };
            elems.push(ElementInfo {
                loc_start,
                ndof: locs.len() - loc_start,
                rule: r,
                law: k,
                thick,
            });
        }
        let mut state_at = Vec::with_capacity(elems.len() + 1);
        state_at.push(0);
        let mut material_state = Vec::new();
        for info in &elems {
            let law = &laws[info.law];
            let sl = law.state_len();
            let npts = if sl == 0 { 0 } else { rules[info.rule].len() };
            for _ in 0..npts {
                let at = material_state.len();
                material_state.resize(at + sl, 0.0);
                law.initial_state(&mut material_state[at..]);
            }
            state_at.push(material_state.len());
        }
        // Small strain and no law with a state: the elements' stiffness is constant.
        let constant_stiffness =
            model.elements.iter().all(|e| !e.nlgeo) && !laws.iter().any(|l| l.is_inelastic());
        let mut a = Assembler {
            model,
            dofs,
            pattern: Pattern {
                n: 0,
                col_ptr: vec![0],
                row_idx: vec![],
                symmetric: true,
            },
            elems,
            locs,
            rules,
            laws,
            couplings: Vec::new(),
            linear_k: std::sync::Mutex::new(None),
            share: None,
            element_scale: 1.0,
            constant_stiffness,
            state_at,
            material_state,
        };
        a.pattern = a.build_pattern();
        Ok(a)
    }

    /// The state `u` as contact sees it: node positions, location codes and multipliers.
    pub fn nodal_state<'u>(&self, u: &'u [f64]) -> NodalState<'u>
    where
        'm: 'u,
    {
        NodalState::new(self.model, self.dofs, u)
    }

    /// Whether the elements' stiffness is constant (small strain, no law with a state): the
    /// bodies' tangent is then the same at every state.
    pub fn constant_stiffness(&self) -> bool {
        self.constant_stiffness
    }

    /// Whether any element's material keeps a state (plasticity).
    pub fn has_material_state(&self) -> bool {
        !self.material_state.is_empty()
    }

    /// The material state committed with the last converged step: every stateful element's
    /// integration points in turn.
    pub fn material_state(&self) -> &[f64] {
        &self.material_state
    }

    /// Put back a state [`Assembler::material_state`] gave (a cut-back restarts the step from
    /// the state it began with).
    pub fn restore_material_state(&mut self, state: &[f64]) {
        self.material_state.copy_from_slice(state);
    }

    /// Commit the state the deformation `u` leaves (a converged step or substep): every later
    /// evaluation starts from it.
    pub fn commit_material_state(&mut self, u: &[f64]) -> Result<()> {
        let mut next = self.material_state.clone();
        let mut fe = vec![0.0; MAX_DOFS];
        for e in 0..self.elems.len() {
            let (a, b) = (self.state_at[e], self.state_at[e + 1]);
            if a < b {
                self.element(e, u, &mut fe, None, None, Some(&mut next[a..b]))?;
            }
        }
        self.material_state = next;
        Ok(())
    }

    /// Sorted free equations behind a list of location codes.
    fn free_eqs(&self, codes: &[usize], out: &mut Vec<usize>) {
        out.clear();
        for &c in codes {
            out.extend(
                self.dofs
                    .entries(c)
                    .map(|x| x.0)
                    .filter(|&p| p < self.dofs.n_free),
            );
        }
        out.sort_unstable();
        out.dedup();
    }

    /// The elements this process assembles in [`Assembler::evaluate_share`] (one flag per
    /// element).
    pub fn set_share(&mut self, share: Vec<bool>) {
        debug_assert_eq!(share.len(), self.elems.len());
        self.share = Some(share);
    }

    /// Scale the elements' forces and tangent by `scale` in the evaluations to come (1: as they
    /// are): a time step's stiffness-proportional damping δ·Ḟ_int adds δ·c₁ times the
    /// elements' own forces and tangent, where c₁ is the velocity's coefficient of u.
    pub fn set_element_scale(&mut self, scale: f64) {
        self.element_scale = scale;
    }

    /// Set the couplings of the contact pairs (location codes per pair); rebuilds the pattern and
    /// returns true when they changed.
    pub fn set_couplings(&mut self, couplings: &[Vec<usize>]) -> bool {
        let mut norm: Vec<Vec<usize>> = Vec::with_capacity(couplings.len());
        let mut eqs = Vec::new();
        for c in couplings {
            self.free_eqs(c, &mut eqs);
            if eqs.len() > 1 {
                norm.push(eqs.clone());
            }
        }
        norm.sort_unstable();
        norm.dedup();
        if norm == self.couplings {
            return false;
        }
        self.couplings = norm;
        self.pattern = self.build_pattern();
        *self.linear_k.lock().expect("not poisoned") = None;
        true
    }

    /// Store both triangles (a contribution's tangent is not symmetric) or only the upper one;
    /// rebuilds the pattern and returns true when that changes.
    pub fn set_symmetric(&mut self, symmetric: bool) -> bool {
        if self.pattern.symmetric == symmetric {
            return false;
        }
        self.pattern.symmetric = symmetric;
        self.pattern = self.build_pattern();
        *self.linear_k.lock().expect("not poisoned") = None;
        true
    }

    fn build_pattern(&self) -> Pattern {
        let n = self.dofs.n_free;
        let symmetric = self.pattern.symmetric;
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut eqs = Vec::new();
        // Rows of column eqs[j]: eqs[..=j] (upper triangle) or all of eqs.
        let mut add = |eqs: &[usize]| {
            for (j, &c) in eqs.iter().enumerate() {
                cols[c].extend_from_slice(if symmetric { &eqs[..=j] } else { eqs });
            }
        };
        for e in 0..self.elems.len() {
            let info = &self.elems[e];
            self.free_eqs(
                &self.locs[info.loc_start..info.loc_start + info.ndof],
                &mut eqs,
            );
            add(&eqs);
        }
        for eqs in &self.couplings {
            add(eqs);
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx = Vec::new();
        for (c, mut rows) in cols.into_iter().enumerate() {
            rows.push(c); // keep every diagonal so a missing stiffness shows as a zero pivot
            rows.sort_unstable();
            rows.dedup();
            row_idx.extend_from_slice(&rows);
            col_ptr.push(row_idx.len());
        }
        Pattern {
            n,
            col_ptr,
            row_idx,
            symmetric,
        }
    }

    /// Evaluate one element at the primary state `u` into `fe`, `ke` (row-major) and states,
    /// from its committed material state; the state the deformation leaves goes to `trial`
    /// (if given).
    fn element(
        &self,
        e: usize,
        u: &[f64],
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        states: Option<&mut Vec<GpState>>,
        trial: Option<&mut [f64]>,
    ) -> Result<()> {
        let old = &self.material_state[self.state_at[e]..self.state_at[e + 1]];
        let mut scratch = Vec::new();
        let new = match trial {
            Some(t) => t,
            None => {
                scratch.resize(old.len(), 0.0);
                &mut scratch[..]
            }
        };
        let el = &self.model.elements[e];
        let info = &self.elems[e];
        let mut ue = [0.0; MAX_DOFS];
        for (k, &c) in self.locs[info.loc_start..info.loc_start + info.ndof]
            .iter()
            .enumerate()
        {
            ue[k] = self.dofs.value(u, c);
        }
        let fail =
            |gp: usize, msg: String| Error::Solve(format!("element {} (gp {gp}): {msg}", el.label));
        let mut x = [[0.0; 3]; MAX_NODES];
        for (a, &n) in el.nodes.iter().enumerate() {
            x[a] = self.model.nodes[n].coords;
        }
        let x = &x[..el.nodes.len()];
        let law = &self.laws[info.law];
        let ue = &ue[..info.ndof];
        let result = if el.etype.is_truss() {
            let kernel = TrussKernel {
                dim: el.dof_ids().len(),
                axes: truss_axes(el),
                area: info.thick,
                law: law.as_ref(),
            };
            kernel.evaluate_into(x, ue, (old, new), fe, ke, states)
        } else {
            let shape = el.etype.shape();
            let kernel = ContinuumKernel {
                shape,
                nsd: shape.dim(),
                rule: &self.rules[info.rule],
                material: law.as_ref(),
                thick: info.thick,
                nlgeo: el.nlgeo,
                bbar: el.bbar,
                hoop: el.etype.hoop_rule(),
            };
            kernel.evaluate_into(x, ue, (old, new), fe, ke, states)
        };
        result.map_err(|k| fail(k.gp, k.msg))
    }

    /// Add one local contribution (location codes, residual, row-major tangent) to the sink.
    fn scatter(
        &self,
        loc: &[usize],
        fe: &[f64],
        ke: Option<&[f64]>,
        sink: &mut Sink,
        count_ebe: bool,
    ) {
        let nf = self.dofs.n_free;
        for (a, &ca) in loc.iter().enumerate() {
            for (p, wp) in self.dofs.entries(ca) {
                sink.f_int[p] += wp * fe[a];
                if count_ebe && p < nf {
                    sink.ebe[self.dofs.primary_dof_id[p] as usize] += (wp * fe[a]).powi(2);
                }
            }
        }
        let Some(ke) = ke else { return };
        let mut values = sink.k_values.as_deref_mut().map(|values| PatternValues {
            pattern: &self.pattern,
            values,
        });
        self.scatter_tangent(
            loc,
            ke,
            values.as_mut(),
            sink.k_fp_dup.as_deref_mut().zip(sink.dup),
        );
    }

    /// Add a local tangent (row-major over `loc`) to the tangent `kv` and, with prescribed
    /// increments, K_fp·Δu_p to `fp_dup`.
    fn scatter_tangent(
        &self,
        loc: &[usize],
        ke: &[f64],
        mut kv: Option<&mut PatternValues>,
        mut fp_dup: Option<(&mut [f64], &[f64])>,
    ) {
        let nf = self.dofs.n_free;
        let upper = kv.as_ref().is_some_and(|k| k.upper_only());
        let nd = loc.len();
        for (a, &ca) in loc.iter().enumerate() {
            for (p, wp) in self.dofs.entries(ca) {
                if p >= nf {
                    continue;
                }
                for (b, &cb) in loc.iter().enumerate() {
                    let kab = ke[a * nd + b];
                    if kab == 0.0 {
                        continue;
                    }
                    for (q, wq) in self.dofs.entries(cb) {
                        if q < nf {
                            if let Some(kv) = kv.as_mut() {
                                if p <= q || !upper {
                                    kv.add(p, q, wp * wq * kab);
                                }
                            }
                        } else if let Some((kd, d)) = fp_dup.as_mut() {
                            kd[p] += wp * wq * kab * d[q - nf];
                        }
                    }
                }
            }
        }
    }

    /// Add the tangents of `extra` contributions to tangent values on the current pattern (whose
    /// couplings must include them).
    pub fn add_tangents(&self, values: &mut [f64], extra: &[Contribution]) {
        let mut kv = PatternValues {
            pattern: &self.pattern,
            values,
        };
        for c in extra.iter().filter(|c| !c.ke.is_empty()) {
            self.scatter_tangent(&c.codes, &c.ke, Some(&mut kv), None);
        }
    }

    /// The elements' tangent at `u` times `x` over every primary equation (prescribed rows
    /// included): K(u)·x, the rate of the internal forces along a motion x.
    pub fn tangent_product(&self, u: &[f64], x: &[f64]) -> Result<Vec<f64>> {
        let mut y = vec![0.0; self.dofs.n_primary()];
        let (mut fe, mut ke) = (vec![0.0; MAX_DOFS], vec![0.0; MAX_DOFS * MAX_DOFS]);
        for (e, info) in self.elems.iter().enumerate() {
            let nd = info.ndof;
            fe[..nd].iter_mut().for_each(|v| *v = 0.0);
            ke[..nd * nd].iter_mut().for_each(|v| *v = 0.0);
            self.element(e, u, &mut fe[..nd], Some(&mut ke[..nd * nd]), None, None)?;
            let loc = &self.locs[info.loc_start..info.loc_start + nd];
            let xe: Vec<f64> = loc.iter().map(|&c| self.dofs.value(x, c)).collect();
            for (a, &ca) in loc.iter().enumerate() {
                let ya: f64 = (0..nd).map(|b| ke[a * nd + b] * xe[b]).sum();
                for (p, wp) in self.dofs.entries(ca) {
                    y[p] += wp * ya;
                }
            }
        }
        Ok(y)
    }

    /// Add the residuals of `extra` contributions (their tangents left out) to `f_int`.
    pub fn add_residuals(&self, f_int: &mut [f64], extra: &[Contribution]) {
        for c in extra {
            for (a, &ca) in c.codes.iter().enumerate() {
                if let Some(&fa) = c.fe.get(a) {
                    for (p, wp) in self.dofs.entries(ca) {
                        f_int[p] += wp * fa;
                    }
                }
            }
        }
    }

    /// The element loop at primary state `u`, plus the `extra` (contact) contributions.
    pub fn evaluate(
        &self,
        u: &[f64],
        want_k: bool,
        want_states: bool,
        dup: Option<&[f64]>,
        extra: &[Contribution],
    ) -> Result<Evaluation> {
        self.evaluate_elements(u, want_k, want_states, dup, extra, None)
    }

    /// [`Assembler::evaluate`] over this process's share of the elements ([`Assembler::set_share`];
    /// all of them without one), without integration-point states: the internal forces, tangent
    /// and K_fp·Δu_p of those elements alone, for a distributed solve to sum.
    pub fn evaluate_share(
        &self,
        u: &[f64],
        want_k: bool,
        dup: Option<&[f64]>,
        extra: &[Contribution],
    ) -> Result<Evaluation> {
        self.evaluate_elements(u, want_k, false, dup, extra, self.share.as_deref())
    }

    fn evaluate_elements(
        &self,
        u: &[f64],
        want_k: bool,
        want_states: bool,
        dup: Option<&[f64]>,
        extra: &[Contribution],
        share: Option<&[bool]>,
    ) -> Result<Evaluation> {
        let nf = self.dofs.n_free;
        let mut sink = Sink {
            f_int: vec![0.0; self.dofs.n_primary()],
            k_values: want_k.then(|| vec![0.0; self.pattern.nnz()]),
            k_fp_dup: dup.map(|_| vec![0.0; nf]),
            dup,
            ebe: [0.0; 4],
        };
        let mut states = want_states.then(|| Vec::with_capacity(self.elems.len()));
        let need_k = want_k || dup.is_some();
        // Small strain: the element stiffness is constant, reuse it on this pattern (the whole
        // model's; a share's is not kept).
        let cacheable = want_k && dup.is_none() && self.constant_stiffness && share.is_none();
        let assembles = |e: usize| share.is_none_or(|s| s[e]);
        if cacheable {
            if let Some(k) = self.linear_k.lock().expect("not poisoned").as_ref() {
                sink.k_values = Some(k.clone());
            }
        }
        let from_cache = cacheable
            && sink
                .k_values
                .as_ref()
                .is_some_and(|k| k.iter().any(|v| *v != 0.0));
        let elem_k = need_k && !from_cache;
        let n_el = self.elems.len();
        let mut start = 0;
        while start < n_el {
            let end = (start + CHUNK * rayon::current_num_threads().max(1)).min(n_el);
            // Parallel kernels on this block of elements: each task fills one flat buffer with the
            // (fe, ke) of a run of consecutive elements.
            let runs: Vec<(usize, usize)> = (start..end)
                .step_by(RUN)
                .map(|a| (a, (a + RUN).min(end)))
                .collect();
            let results: Vec<Result<RunBuffer>> = runs
                .into_par_iter()
                .map(|(a, b)| {
                    let mut buf = RunBuffer::default();
                    for e in a..b {
                        let off = buf.values.len();
                        buf.offsets.push(off);
                        if !assembles(e) {
                            buf.states.push(Vec::new());
                            continue;
                        }
                        let nd = self.elems[e].ndof;
                        buf.values
                            .resize(off + nd + if elem_k { nd * nd } else { 0 }, 0.0);
                        let (fe, ke) = buf.values[off..].split_at_mut(nd);
                        let mut st = Vec::new();
                        self.element(
                            e,
                            u,
                            fe,
                            elem_k.then_some(ke),
                            want_states.then_some(&mut st),
                            None,
                        )?;
                        buf.states.push(st);
                    }
                    Ok(buf)
                })
                .collect();
            let mut e = start;
            for res in results {
                let buf = res?;
                for (k, st) in buf.states.into_iter().enumerate() {
                    if !assembles(e) {
                        e += 1;
                        continue;
                    }
                    let nd = self.elems[e].ndof;
                    let fe = &buf.values[buf.offsets[k]..buf.offsets[k] + nd];
                    let ke = &buf.values[buf.offsets[k] + nd..];
                    let info = &self.elems[e];
                    let loc = &self.locs[info.loc_start..info.loc_start + info.ndof];
                    self.scatter(loc, fe, elem_k.then_some(ke), &mut sink, true);
                    if let Some(s) = states.as_mut() {
                        s.push(st);
                    }
                    e += 1;
                }
            }
            start = end;
        }
        if cacheable && !from_cache {
            *self.linear_k.lock().expect("not poisoned") = sink.k_values.clone();
        }
        let scale = self.element_scale;
        if scale != 1.0 {
            let vectors = [
                Some(&mut sink.f_int),
                sink.k_values.as_mut(),
                sink.k_fp_dup.as_mut(),
            ];
            for v in vectors.into_iter().flatten() {
                v.iter_mut().for_each(|x| *x *= scale);
            }
            sink.ebe.iter_mut().for_each(|x| *x *= scale * scale);
        }
        for c in extra {
            if !c.fe.is_empty() {
                self.scatter(
                    &c.codes,
                    &c.fe,
                    need_k.then_some(c.ke.as_slice()),
                    &mut sink,
                    false,
                );
            }
        }
        Ok(Evaluation {
            f_int: sink.f_int,
            k_values: sink.k_values,
            k_fp_dup: sink.k_fp_dup,
            ebe: sink.ebe,
            states,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two distorted plane stress quadrilaterals in large deformation (St. Venant–Kirchhoff),
    /// node 1 held.
    fn two_quads() -> Model {
        let text = "m.out\nquads\nNonLinearStatic nsteps 1 controlmode 1\n\
                    domain 2dPlaneStress\nOutputManager\n\
                    ndofman 6 nelem 2 ncrosssect 1 nmat 1 nbc 1 nic 0 nltf 1 nset 2\n\
                    node 1 coords 2 0 0\nnode 2 coords 2 1 0\nnode 3 coords 2 2.1 0.1\n\
                    node 4 coords 2 0 1\nnode 5 coords 2 1.1 1.2\nnode 6 coords 2 2 1\n\
                    PlaneStress2d 1 nodes 4 1 2 5 4 crossSect 1 mat 1 nlgeo 1\n\
                    PlaneStress2d 2 nodes 4 2 3 6 5 crossSect 1 mat 1 nlgeo 1\n\
                    SimpleCS 1 thick 0.3 material 1 set 1\nIsoLE 1 d 2.5 E 7 n 0.3 tAlpha 0\n\
                    BoundaryCondition 1 loadTimeFunction 1 dofs 2 1 2 values 2 0 0 set 2\n\
                    ConstantFunction 1 f(t) 1\nSet 1 allelements\nSet 2 nodes 1 1\n";
        crate::input::read_model_str(text, "m.in").unwrap().model
    }

    /// The elements' scale (stiffness-proportional damping) multiplies their forces and
    /// tangent and leaves the extra (contact) contributions as they are.
    #[test]
    fn the_element_scale_leaves_the_extra_contributions_alone() {
        let model = two_quads();
        let dofs = DofMap::new(&model, &Default::default()).unwrap();
        let mut asm = Assembler::new(&model, &dofs).unwrap();
        let np = dofs.n_primary();
        let u: Vec<f64> = (0..np).map(|i| 0.05 * (i as f64).cos()).collect();
        let extra = [Contribution {
            codes: vec![dofs.code(2, 1).unwrap(), dofs.code(2, 2).unwrap()],
            fe: vec![1.0, 2.0],
            ke: vec![3.0, 0.0, 0.0, 4.0],
        }];
        asm.set_couplings(&[extra[0].codes.clone()]);
        let plain = asm.evaluate(&u, true, false, None, &[]).unwrap();
        let with = asm.evaluate(&u, true, false, None, &extra).unwrap();
        asm.set_element_scale(2.5);
        let scaled = asm.evaluate(&u, true, false, None, &extra).unwrap();
        for i in 0..np {
            let expect = 2.5 * plain.f_int[i] + (with.f_int[i] - plain.f_int[i]);
            assert!((scaled.f_int[i] - expect).abs() < 1e-12, "{i}");
        }
        let (kp, kw, ks) = (
            plain.k_values.unwrap(),
            with.k_values.unwrap(),
            scaled.k_values.unwrap(),
        );
        for i in 0..kp.len() {
            let expect = 2.5 * kp[i] + (kw[i] - kp[i]);
            assert!((ks[i] - expect).abs() < 1e-12, "{i}");
        }
    }

    /// K(u)·x is the derivative of the elements' forces along x (central differences), on
    /// every primary equation, the held node's rows and columns included.
    #[test]
    fn the_tangent_product_is_the_derivative_of_the_forces_along_a_motion() {
        let model = two_quads();
        let dofs = DofMap::new(&model, &Default::default()).unwrap();
        let asm = Assembler::new(&model, &dofs).unwrap();
        let np = dofs.n_primary();
        let u: Vec<f64> = (0..np).map(|i| 0.05 * (i as f64).cos()).collect();
        let x: Vec<f64> = (0..np).map(|i| (0.7 * i as f64).sin()).collect();
        let y = asm.tangent_product(&u, &x).unwrap();
        let h = 1e-6;
        let force = |s: f64| {
            let v: Vec<f64> = u.iter().zip(&x).map(|(a, b)| a + s * b).collect();
            asm.evaluate(&v, false, false, None, &[]).unwrap().f_int
        };
        let (plus, minus) = (force(h), force(-h));
        let scale = y.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..np {
            let fd = (plus[i] - minus[i]) / (2.0 * h);
            assert!((fd - y[i]).abs() < 1e-7 * scale, "{i}: {} vs {fd}", y[i]);
        }
        assert!(scale > 0.1, "{scale}");
    }
}
