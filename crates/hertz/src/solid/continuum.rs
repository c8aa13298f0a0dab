//! Continuum element kernel for every 2D/3D shape and every material law: small strain, or
//! total Lagrangian (`nlgeo 1`: Green–Lagrange strain E = ½(FᵀF − I), the law's second
//! Piola–Kirchhoff stress S(E) and tangent D = dS/dE, f_ai = ∫ F_iI S_IJ ∂N_a/∂X_J and the
//! consistent tangent ∫ Bᵀ D B plus the geometric stiffness ∫ ∂N_a/∂X_I S_IJ ∂N_b/∂X_J δ_ik).
//!
//! Glossary: `nsd` space dimensions; `x_ref[a]` reference coordinates of node a; `u[a*nsd+i]`
//! displacement; `dndx[a][I]` = ∂N_a/∂X_I; `f` = F (deformation gradient, 3×3, F₃₃ = 1 in 2D);
//! `s` = second Piola–Kirchhoff stress tensor; `jxw` = |det J|·weight·thickness.

use super::kernel::{ElementKernel, GpState, KernelError};
use crate::fem::geometry::{det3, map_derivatives};
use crate::fem::{QuadPoint, Shape};
use crate::material::{voigt_components_of, PointLaw, Response, VOIGT_PAIRS};
use crate::model::HoopRule;

/// Maximum nodes and DOFs per element.
pub use crate::fem::{MAX_DOFS, MAX_NODES};

/// Everything a continuum kernel needs besides nodal data.
pub struct ContinuumKernel<'a> {
    pub shape: Shape,
    pub nsd: usize,
    pub rule: &'a [QuadPoint],
    pub material: &'a dyn PointLaw,
    /// Thickness for 2D elements (1 in 3D).
    pub thick: f64,
    pub nlgeo: bool,
    /// The volumetric deformation of every point the element's mean: B-bar in small strain,
    /// F-bar in large deformation (see [`super::barred`]).
    pub bbar: bool,
    /// Axisymmetric (x = r, y = z): the hoop strain u_r/r in the out-of-plane place, every
    /// integral per radian (weighted by r, `thick` unused); where the hoop strain and the shear
    /// are taken in small strain (in large deformation at every point: F₃₃ = 1 + u_r/R).
    pub hoop: Option<HoopRule>,
}

/// An axisymmetric point's hoop and shear rows: ∂u_r/r per node (N_a/r at the point or
/// N_a(0)/r_c at the centroid), and with the centroid rule ∂N_a/∂X there for γ_rz.
struct Hoop {
    n_over_r: [f64; MAX_NODES],
    shear: Option<[[f64; 3]; MAX_NODES]>,
}

impl ElementKernel for ContinuumKernel<'_> {
    /// Internal force `fe` (len nnode·nsd) and, if requested, tangent `ke` (row-major square)
    /// and integration-point states; `old` the material's committed state of every integration
    /// point in turn (its `state_len` numbers each), `new` the state this deformation leaves.
    fn evaluate_into(
        &self,
        x_ref: &[[f64; 3]],
        u: &[f64],
        (old, new): (&[f64], &mut [f64]),
        fe: &mut [f64],
        mut ke: Option<&mut [f64]>,
        mut states: Option<&mut Vec<GpState>>,
    ) -> Result<(), KernelError> {
        let sl = self.material.state_len();
        let nsd = self.nsd;
        let nn = self.shape.n_nodes();
        let ndof = nn * nsd;
        fe[..ndof].fill(0.0);
        if let Some(k) = ke.as_deref_mut() {
            k[..ndof * ndof].fill(0.0);
        }
        let mut n = [0.0; MAX_NODES];
        let mut dn = [[0.0; 3]; MAX_NODES];
        let mut dndx = [[0.0; 3]; MAX_NODES];
        // B and D·B rows, one pair of buffers for all points (only the first ndof entries used).
        let mut b = [[0.0; MAX_DOFS]; 6];
        let mut db = [[0.0; MAX_DOFS]; 6];
        let means = match self.bbar {
            true => Some(super::barred::means(
                (self.shape, self.nsd, self.rule),
                self.nlgeo,
                x_ref,
                u,
            )?),
            false => None,
        };
        let centroid = match self.hoop {
            Some(HoopRule::Centroid) if !self.nlgeo => Some(self.centroid_rows(x_ref)?),
            _ => None,
        };
        for (g, qp) in self.rule.iter().enumerate() {
            self.shape.eval(qp.xi, &mut n, &mut dn);
            let det =
                map_derivatives(nsd, nn, x_ref, &dn, &mut dndx).ok_or_else(|| KernelError {
                    gp: g + 1,
                    msg: "degenerate element geometry (det J = 0)".into(),
                })?;
            let mut jxw = det.abs() * qp.weight * self.thick;
            let mut h = gradient(u, &dndx, nn, nsd);
            // Axisymmetric: the hoop rows at the point, unless the centroid's serve every point.
            let pointwise: Option<Hoop>;
            let hoop = match self.hoop {
                Some(_) => {
                    let r = self
                        .radius_at(&n, x_ref)
                        .map_err(|msg| KernelError { gp: g + 1, msg })?;
                    jxw = det.abs() * qp.weight * r;
                    pointwise = centroid.is_none().then(|| Hoop::at_point(&n, nn, r));
                    let hoop = centroid.as_ref().or(pointwise.as_ref());
                    hoop.inspect(|hoop| hoop.add_to_gradient(u, nn, &mut h))
                }
                None => None,
            };
            let (f, mut e) = deformation(&h, self.nlgeo);
            if self.nlgeo && det3(&f) <= 0.0 {
                return Err(KernelError {
                    gp: g + 1,
                    msg: format!("element inverted (det F = {:.3e})", det3(&f)),
                });
            }
            let slice = |g: usize| g * sl..(g + 1) * sl;
            if let (Some(c), true) = (&means, self.nlgeo) {
                let point = super::barred::FbarPoint {
                    nsd: self.nsd,
                    dndx: &dndx,
                    f,
                    jxw,
                    nn,
                };
                super::barred::fbar_point(
                    self.material,
                    c,
                    &point,
                    (&old[slice(g)], &mut new[slice(g)]),
                    fe,
                    ke.as_deref_mut(),
                    states.as_deref_mut(),
                )
                .map_err(|msg| KernelError { gp: g + 1, msg })?;
                continue;
            }
            if let Some(c) = &means {
                // B-bar: the element's mean volumetric strain θ̄ in place of the point's.
                let theta = h[0][0] + h[1][1] + h[2][2];
                for (k, row) in e.iter_mut().enumerate() {
                    row[k] += (c.theta - theta) / 3.0;
                }
            }
            let point = Point {
                dndx: &dndx,
                f,
                e,
                jxw,
                nn,
                mean: means.as_ref().map(|c| &c.dndx),
                hoop,
            };
            self.point(
                (&old[slice(g)], &mut new[slice(g)]),
                &point,
                fe,
                ke.as_deref_mut(),
                (&mut b, &mut db),
                states.as_deref_mut(),
            )
            .map_err(|msg| KernelError { gp: g + 1, msg })?;
        }
        Ok(())
    }
}

/// The displacement gradient H = ∂u/∂X at a point.
fn gradient(u: &[f64], dndx: &[[f64; 3]; MAX_NODES], nn: usize, nsd: usize) -> [[f64; 3]; 3] {
    let mut h = [[0.0; 3]; 3];
    for a in 0..nn {
        for i in 0..nsd {
            for j in 0..nsd {
                h[i][j] += u[a * nsd + i] * dndx[a][j];
            }
        }
    }
    h
}

/// F = I + H and the strain: ½(H + Hᵀ) in small strain, E = ½(H + Hᵀ + HᵀH) with `nlgeo`.
fn deformation(h: &[[f64; 3]; 3], nlgeo: bool) -> ([[f64; 3]; 3], [[f64; 3]; 3]) {
    let mut f = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let mut e = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            f[i][j] += h[i][j];
            e[i][j] = 0.5 * (h[i][j] + h[j][i]);
            if nlgeo {
                e[i][j] += 0.5 * (0..3).map(|k| h[k][i] * h[k][j]).sum::<f64>();
            }
        }
    }
    (f, e)
}

/// The shape functions and the volume element dV (with the thickness `thick`, or per radian the
/// radius where it is None) at every point of `rule` on the reference element, handed to `f`.
fn for_each_point(
    shape: Shape,
    rule: &[QuadPoint],
    thick: Option<f64>,
    x_ref: &[[f64; 3]],
    mut f: impl FnMut(&[f64], f64),
) -> Result<(), KernelError> {
    let nn = shape.n_nodes();
    let mut n = [0.0; MAX_NODES];
    let mut dn = [[0.0; 3]; MAX_NODES];
    let mut dndx = [[0.0; 3]; MAX_NODES];
    for (g, qp) in rule.iter().enumerate() {
        shape.eval(qp.xi, &mut n, &mut dn);
        let det =
            map_derivatives(shape.dim(), nn, x_ref, &dn, &mut dndx).ok_or_else(|| KernelError {
                gp: g + 1,
                msg: "degenerate element geometry (det J = 0)".into(),
            })?;
        let weight = thick.unwrap_or_else(|| (0..nn).map(|a| n[a] * x_ref[a][0]).sum());
        f(&n[..nn], det.abs() * qp.weight * weight);
    }
    Ok(())
}

/// ∫ N_a dV for each node of an element (for body forces): `thick` in 2D, or with None per
/// radian of an axisymmetric element (dV = r dA).
pub fn integrate_shape(
    shape: Shape,
    rule: &[QuadPoint],
    thick: Option<f64>,
    x_ref: &[[f64; 3]],
    out: &mut [f64],
) -> Result<(), KernelError> {
    let nn = shape.n_nodes();
    out[..nn].fill(0.0);
    for_each_point(shape, rule, thick, x_ref, |n, dv| {
        for a in 0..nn {
            out[a] += n[a] * dv;
        }
    })
}

/// ∫ N_a N_b dV over the reference element (row-major, nodes × nodes), as
/// [`integrate_shape`] weights it: the scalar block of the consistent mass per unit density.
pub fn integrate_shape_products(
    shape: Shape,
    rule: &[QuadPoint],
    thick: Option<f64>,
    x_ref: &[[f64; 3]],
) -> Result<Vec<f64>, KernelError> {
    let nn = shape.n_nodes();
    let mut out = vec![0.0; nn * nn];
    for_each_point(shape, rule, thick, x_ref, |n, dv| {
        for a in 0..nn {
            for b in 0..nn {
                out[a * nn + b] += n[a] * n[b] * dv;
            }
        }
    })?;
    Ok(out)
}

/// Kinematics at one integration point.
struct Point<'a> {
    dndx: &'a [[f64; 3]; MAX_NODES],
    f: [[f64; 3]; 3],
    /// Green–Lagrange strain (small strain: the symmetric gradient).
    e: [[f64; 3]; 3],
    jxw: f64,
    nn: usize,
    /// B-bar: the element's mean ∂N_a/∂X_I, whose volumetric strain the point takes.
    mean: Option<&'a [[f64; 3]; MAX_NODES]>,
    /// Axisymmetric: the hoop (and centroid shear) rows.
    hoop: Option<&'a Hoop>,
}

impl Hoop {
    /// The rows of a point with shape functions `n` (of `nn` nodes) at radius `r`: N_a/r.
    fn at_point(n: &[f64; MAX_NODES], nn: usize, r: f64) -> Hoop {
        Hoop {
            n_over_r: std::array::from_fn(|a| if a < nn { n[a] / r } else { 0.0 }),
            shear: None,
        }
    }

    /// The hoop strain's (and with the centroid rule the shear's) part of the displacement
    /// gradient `h`: H₃₃ = u_r/r, H_rz and H_zr from the centroid's gradient.
    fn add_to_gradient(&self, u: &[f64], nn: usize, h: &mut [[f64; 3]; 3]) {
        h[2][2] = (0..nn).map(|a| u[a * 2] * self.n_over_r[a]).sum();
        if let Some(dc) = &self.shear {
            h[0][1] = (0..nn).map(|a| u[a * 2] * dc[a][1]).sum();
            h[1][0] = (0..nn).map(|a| u[a * 2 + 1] * dc[a][0]).sum();
        }
    }
}

impl ContinuumKernel<'_> {
    /// The radius r of an axisymmetric point, from its shape functions `n`.
    fn radius_at(&self, n: &[f64; MAX_NODES], x_ref: &[[f64; 3]]) -> Result<f64, String> {
        let r: f64 = (0..self.shape.n_nodes()).map(|a| n[a] * x_ref[a][0]).sum();
        match r > 0.0 {
            true => Ok(r),
            false => Err(format!("an axisymmetric point at radius {r:.3e} ≤ 0")),
        }
    }

    /// The centroid's hoop and shear rows of an axisymmetric element (OOFEM's rule).
    fn centroid_rows(&self, x_ref: &[[f64; 3]]) -> Result<Hoop, KernelError> {
        let nn = self.shape.n_nodes();
        let (mut n, mut dn) = ([0.0; MAX_NODES], [[0.0; 3]; MAX_NODES]);
        let mut dndx = [[0.0; 3]; MAX_NODES];
        self.shape.eval(self.shape.centroid(), &mut n, &mut dn);
        map_derivatives(self.nsd, nn, x_ref, &dn, &mut dndx).ok_or_else(|| KernelError {
            gp: 0,
            msg: "degenerate element geometry at its centroid (det J = 0)".into(),
        })?;
        let r: f64 = (0..nn).map(|a| n[a] * x_ref[a][0]).sum();
        if !(r > 0.0) {
            return Err(KernelError {
                gp: 0,
                msg: format!("an axisymmetric element's centroid at radius {r:.3e} ≤ 0"),
            });
        }
        Ok(Hoop {
            n_over_r: std::array::from_fn(|a| if a < nn { n[a] / r } else { 0.0 }),
            shear: Some(dndx),
        })
    }

    /// The material's response at a point: σ(ε), or S(E) with the geometric stiffness.
    fn point(
        &self,
        (old, new): (&[f64], &mut [f64]),
        pt: &Point,
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        buffers: (&mut [[f64; MAX_DOFS]; 6], &mut [[f64; MAX_DOFS]; 6]),
        states: Option<&mut Vec<GpState>>,
    ) -> Result<(), String> {
        let law = self.material;
        let nc = law.components();
        let comps = voigt_components_of(nc);
        let mut strain = [0.0; 6];
        for (k, &c) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[c];
            strain[k] = if i == j { pt.e[i][j] } else { 2.0 * pt.e[i][j] };
        }
        let mut answer = Answer {
            comps,
            strain,
            stress: [0.0; 6],
            tangent: [0.0; 36],
            normal_strain: 0.0,
            s: [[0.0; 3]; 3],
            fm: if self.nlgeo {
                pt.f
            } else {
                [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
            },
        };
        let mut out = Response {
            stress: &mut answer.stress[..nc],
            tangent: &mut answer.tangent[..nc * nc],
            state: new,
            normal_strain: 0.0,
        };
        law.respond(&strain[..nc], old, &mut out)?;
        answer.normal_strain = out.normal_strain;
        for (k, &c) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[c];
            answer.s[i][j] = answer.stress[k];
            answer.s[j][i] = answer.stress[k];
        }
        self.add_force(pt, &answer, fe);
        if let Some(k) = ke {
            self.add_material_tangent(pt, &answer, k, buffers);
            if self.nlgeo {
                self.add_geometric_tangent(pt, &answer.s, k);
            }
        }
        if let Some(st) = states {
            let mut state = self.point_state(pt, &answer);
            state.plastic = law.plastic(new);
            st.push(state);
        }
        Ok(())
    }

    /// f_ai += ∫ F_iI S_IJ ∂N_a/∂X_J.
    fn add_force(&self, pt: &Point, answer: &Answer, fe: &mut [f64]) {
        let (nsd, fm, s) = (self.nsd, &answer.fm, &answer.s);
        let mut fs = [[0.0; 3]; 3];
        for i in 0..nsd {
            for jj in 0..nsd {
                fs[i][jj] = (0..nsd).map(|ii| fm[i][ii] * s[ii][jj]).sum();
            }
        }
        for a in 0..pt.nn {
            for i in 0..nsd {
                fe[a * nsd + i] +=
                    pt.jxw * (0..nsd).map(|jj| fs[i][jj] * pt.dndx[a][jj]).sum::<f64>();
            }
        }
        if let Some(hoop) = pt.hoop {
            // The hoop stress through δε_θ = F₃₃ δu_r/r; with the centroid rule the shear
            // through the centroid's gradient instead of the point's (small strain: F = I).
            for a in 0..pt.nn {
                fe[a * nsd] += pt.jxw * fm[2][2] * s[2][2] * hoop.n_over_r[a];
                if let Some(dc) = &hoop.shear {
                    fe[a * nsd] += pt.jxw * s[0][1] * (dc[a][1] - pt.dndx[a][1]);
                    fe[a * nsd + 1] += pt.jxw * s[0][1] * (dc[a][0] - pt.dndx[a][0]);
                }
            }
        }
        if let Some(d0) = pt.mean {
            // B̄ᵀσ: the mean stress acts through the mean volumetric row.
            let mean = (s[0][0] + s[1][1] + s[2][2]) / 3.0;
            for a in 0..pt.nn {
                for i in 0..nsd {
                    fe[a * nsd + i] += pt.jxw * mean * (d0[a][i] - pt.dndx[a][i]);
                }
            }
        }
    }

    /// k += ∫ Bᵀ D B, B the strain's variation (δE_k = B_k · δu) with F in large deformation,
    /// into `b` and D·B into `db`.
    fn add_material_tangent(
        &self,
        pt: &Point,
        answer: &Answer,
        k: &mut [f64],
        (b, db): (&mut [[f64; MAX_DOFS]; 6], &mut [[f64; MAX_DOFS]; 6]),
    ) {
        let (nsd, nn, dndx, fm) = (self.nsd, pt.nn, pt.dndx, &answer.fm);
        let (ndof, nc) = (nn * nsd, answer.comps.len());
        for (row, &c) in answer.comps.iter().enumerate() {
            let (ii, jj) = VOIGT_PAIRS[c];
            for a in 0..nn {
                for i in 0..nsd {
                    b[row][a * nsd + i] = if ii == jj {
                        fm[i][ii] * dndx[a][ii]
                    } else {
                        fm[i][ii] * dndx[a][jj] + fm[i][jj] * dndx[a][ii]
                    };
                }
            }
        }
        if let Some(hoop) = pt.hoop {
            for (row, &c) in answer.comps.iter().enumerate() {
                match (c, &hoop.shear) {
                    (2, _) => {
                        for a in 0..nn {
                            b[row][a * nsd] = fm[2][2] * hoop.n_over_r[a];
                            b[row][a * nsd + 1] = 0.0;
                        }
                    }
                    (5, Some(dc)) => {
                        for a in 0..nn {
                            b[row][a * nsd] = dc[a][1];
                            b[row][a * nsd + 1] = dc[a][0];
                        }
                    }
                    _ => {}
                }
            }
        }
        if let Some(d0) = pt.mean {
            // B̄ = B + ⅓ m ⊗ (b₀ − b) on the normal components.
            for (row, &c) in answer.comps.iter().enumerate() {
                if c < 3 {
                    for a in 0..nn {
                        for i in 0..nsd {
                            b[row][a * nsd + i] += (d0[a][i] - dndx[a][i]) / 3.0;
                        }
                    }
                }
            }
        }
        // The rows of B that can be non-zero: in 2D not those of a component with z (the
        // plane-strain ε_zz, whose row vanishes but with B-bar and the axisymmetric hoop).
        let mut rows = [0usize; 6];
        let mut nr = 0;
        let zz = pt.mean.is_some() || pt.hoop.is_some();
        for (row, &c) in answer.comps.iter().enumerate() {
            let (ii, jj) = VOIGT_PAIRS[c];
            if (ii < nsd && jj < nsd) || (zz && c < 3) {
                rows[nr] = row;
                nr += 1;
            }
        }
        let rows = &rows[..nr];
        let d = &answer.tangent;
        for &r in rows {
            for q in 0..ndof {
                db[r][q] = rows.iter().map(|&t| d[r * nc + t] * b[t][q]).sum::<f64>() * pt.jxw;
            }
        }
        // Bᵀ D B, one triangle mirrored where D is symmetric.
        let symmetric = self.material.symmetric_tangent();
        for p in 0..ndof {
            for q in if symmetric { p } else { 0 }..ndof {
                let mut v = 0.0;
                for &r in rows {
                    v += b[r][p] * db[r][q];
                }
                k[p * ndof + q] += v;
                if symmetric && q > p {
                    k[q * ndof + p] += v;
                }
            }
        }
    }

    /// k += ∫ ∂N_a/∂X_I S_IJ ∂N_b/∂X_J δ_ik, the geometric stiffness of large deformation.
    fn add_geometric_tangent(&self, pt: &Point, s: &[[f64; 3]; 3], k: &mut [f64]) {
        let (nsd, nn, dndx) = (self.nsd, pt.nn, pt.dndx);
        let ndof = nn * nsd;
        for a in 0..nn {
            for bb in 0..nn {
                let mut gab = 0.0;
                for ii in 0..nsd {
                    for jj in 0..nsd {
                        gab += dndx[a][ii] * s[ii][jj] * dndx[bb][jj];
                    }
                }
                for i in 0..nsd {
                    k[(a * nsd + i) * ndof + bb * nsd + i] += pt.jxw * gab;
                }
                if let Some(hoop) = pt.hoop {
                    // S₃₃ δF₃₃ ΔF₃₃, δF₃₃ = δu_r/R.
                    k[(a * nsd) * ndof + bb * nsd] +=
                        pt.jxw * s[2][2] * hoop.n_over_r[a] * hoop.n_over_r[bb];
                }
            }
        }
    }

    /// The point's results in full Voigt form, with F and P = F S.
    fn point_state(&self, pt: &Point, answer: &Answer) -> GpState {
        let nc = answer.comps.len();
        let mut f = pt.f;
        let mut full_e = [0.0; 6];
        let mut full_s = [0.0; 6];
        for (k, &c) in answer.comps.iter().enumerate() {
            full_e[c] = answer.strain[k];
            full_s[c] = answer.stress[k];
        }
        if nc == 4 && pt.mean.is_none() && pt.hoop.is_none() {
            // Plane strain: ε_zz = 0 whatever the reduced vector carries (B-bar's and the
            // axisymmetric hoop strain are not).
            full_e[2] = 0.0;
        }
        if nc == 3 && answer.normal_strain != 0.0 {
            // Plane stress: the normal strain the law found, and its stretch in F.
            full_e[2] = answer.normal_strain;
            if self.nlgeo {
                f[2][2] = (1.0 + 2.0 * answer.normal_strain).sqrt();
            }
        }
        let mut p = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                p[i][j] = (0..3).map(|t| answer.fm[i][t] * answer.s[t][j]).sum();
            }
        }
        GpState {
            strain: full_e,
            stress: full_s,
            f,
            p,
            plastic: None,
        }
    }
}

/// A law's answer at a point: its strain and stress (reduced Voigt form, `comps` the full
/// components they are) and tangent, the stress as a tensor `s`, and the F of the element's
/// forces `fm` (the identity in small strain).
struct Answer {
    comps: &'static [usize],
    strain: [f64; 6],
    stress: [f64; 6],
    tangent: [f64; 36],
    normal_strain: f64,
    s: [[f64; 3]; 3],
    fm: [[f64; 3]; 3],
}
