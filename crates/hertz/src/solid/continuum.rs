//! Continuum element kernel for every 2D/3D shape: small strain, or total Lagrangian
//! (`nlgeo 1`: Green–Lagrange strain E = ½(FᵀF − I), S = D:E for linear elasticity, consistent
//! tangent with the geometric stiffness; for a hyperelastic law the first Piola–Kirchhoff stress
//! P(F) and A = ∂P/∂F: f_ai = ∫ P_iJ ∂N_a/∂X_J, K_aibk = ∫ ∂N_a/∂X_J A_iJkL ∂N_b/∂X_L).
//!
//! Glossary: `nsd` space dimensions; `x_ref[a]` reference coordinates of node a; `u[a*nsd+i]`
//! displacement; `dndx[a][I]` = ∂N_a/∂X_I; `f` = F (deformation gradient, 3×3, F₃₃ = 1 in 2D);
//! `s` = second Piola–Kirchhoff stress tensor; `jxw` = |det J|·weight·thickness.

use crate::fem::geometry::{det3, inverse3, map_derivatives};
use crate::fem::{QuadPoint, Shape};
use crate::material::{voigt_components_of, Constitutive, Hyperelastic, PointLaw, VOIGT_PAIRS};

/// Maximum nodes and DOFs per element.
pub use crate::fem::MAX_NODES;
pub const MAX_DOFS: usize = 3 * MAX_NODES;

/// Results at one integration point, in full 6-component Voigt form (spec §1.17).
#[derive(Debug, Clone, Copy, Default)]
pub struct GpState {
    /// Small strain, or Green–Lagrange strain E for nlgeo.
    pub strain: [f64; 6],
    /// Cauchy stress (small strain), or second Piola–Kirchhoff S.
    pub stress: [f64; 6],
    /// Deformation gradient, row-major 3×3.
    pub f: [[f64; 3]; 3],
    /// First Piola–Kirchhoff stress P = F·S, row-major 3×3.
    pub p: [[f64; 3]; 3],
}

/// Everything a continuum kernel needs besides nodal data.
pub struct ContinuumKernel<'a> {
    pub shape: Shape,
    pub nsd: usize,
    pub rule: &'a [QuadPoint],
    pub material: &'a Constitutive,
    /// Thickness for 2D elements (1 in 3D).
    pub thick: f64,
    pub nlgeo: bool,
}

/// A failed evaluation: degenerate reference geometry or an inverted element.
#[derive(Debug, Clone)]
pub struct KernelError {
    pub gp: usize,
    pub msg: String,
}

impl super::kernel::ElementKernel for ContinuumKernel<'_> {
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
        let mut b = [[0.0; MAX_DOFS]; 6];
        for (g, qp) in self.rule.iter().enumerate() {
            self.shape.eval(qp.xi, &mut n, &mut dn);
            let det =
                map_derivatives(nsd, nn, x_ref, &dn, &mut dndx).ok_or_else(|| KernelError {
                    gp: g + 1,
                    msg: "degenerate element geometry (det J = 0)".into(),
                })?;
            let jxw = det.abs() * qp.weight * self.thick;
            // Deformation gradient F = I + ∂u/∂X.
            let mut f = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            let mut h = [[0.0; 3]; 3];
            for a in 0..nn {
                for i in 0..nsd {
                    for j in 0..nsd {
                        h[i][j] += u[a * nsd + i] * dndx[a][j];
                    }
                }
            }
            for i in 0..3 {
                for j in 0..3 {
                    f[i][j] += h[i][j];
                }
            }
            let mut e = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    e[i][j] = 0.5 * (h[i][j] + h[j][i]);
                    if self.nlgeo {
                        e[i][j] += 0.5 * (0..3).map(|k| h[k][i] * h[k][j]).sum::<f64>();
                    }
                }
            }
            if self.nlgeo && det3(&f) <= 0.0 {
                return Err(KernelError {
                    gp: g + 1,
                    msg: format!("element inverted (det F = {:.3e})", det3(&f)),
                });
            }
            let point = Point {
                dndx: &dndx,
                f,
                e,
                jxw,
                nn,
            };
            match self.material {
                Constitutive::Small(law) => self.linear_point(
                    law.as_ref(),
                    (&old[g * sl..(g + 1) * sl], &mut new[g * sl..(g + 1) * sl]),
                    &point,
                    fe,
                    ke.as_deref_mut(),
                    &mut b,
                    states.as_deref_mut(),
                ),
                Constitutive::Hyper(h) => self
                    .hyperelastic_point(h, &point, fe, ke.as_deref_mut(), states.as_deref_mut())
                    .map_err(|msg| KernelError { gp: g + 1, msg })?,
                Constitutive::HyperPlaneStress(h) => {
                    let mut point = point;
                    let stretch = plane_stress_stretch(h, &point.f)
                        .map_err(|msg| KernelError { gp: g + 1, msg })?;
                    point.f[2][2] = stretch;
                    point.e[2][2] = 0.5 * (stretch * stretch - 1.0);
                    self.hyperelastic_point(h, &point, fe, ke.as_deref_mut(), states.as_deref_mut())
                        .map_err(|msg| KernelError { gp: g + 1, msg })?
                }
            }
        }
        Ok(())
    }
}

/// The out-of-plane stretch F₃₃ of a plane-stress point whose in-plane deformation is `f` (its
/// F₃₃ ignored): the root of P₃₃(F₃₃) = 0, by Newton's method from the stretch that keeps the
/// volume, with steps halved to keep F₃₃ positive.
fn plane_stress_stretch(h: &Hyperelastic, f: &[[f64; 3]; 3]) -> Result<f64, String> {
    let det2 = f[0][0] * f[1][1] - f[0][1] * f[1][0];
    if !(det2 > 0.0) {
        return Err(format!("element inverted (in-plane det F = {det2:.3e})"));
    }
    let mut g = *f;
    g[2][2] = 1.0 / det2.sqrt();
    let mut scale = 0.0f64;
    for _ in 0..60 {
        let (p, a) = h
            .pk1(&g)
            .map_err(|det| format!("element inverted (det F = {det:.3e})"))?;
        scale = scale.max(p.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())));
        let r = p[2][2];
        if r.abs() <= 1e-14 * scale.max(f64::MIN_POSITIVE) {
            return Ok(g[2][2]);
        }
        let mut step = -r / a[2][2][2][2];
        while g[2][2] + step <= 0.0 {
            step *= 0.5;
        }
        g[2][2] += step;
        if step.abs() <= 1e-15 * g[2][2] {
            return Ok(g[2][2]);
        }
    }
    Err("plane stress: the out-of-plane stretch did not converge".into())
}

/// ∫ N_a dV for each node of an element (for body forces), `thick` in 2D.
pub fn integrate_shape(
    shape: Shape,
    rule: &[QuadPoint],
    thick: f64,
    x_ref: &[[f64; 3]],
    out: &mut [f64],
) -> Result<(), KernelError> {
    let nn = shape.n_nodes();
    out[..nn].fill(0.0);
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
        for a in 0..nn {
            out[a] += n[a] * det.abs() * qp.weight * thick;
        }
    }
    Ok(())
}

/// Kinematics at one integration point.
struct Point<'a> {
    dndx: &'a [[f64; 3]; MAX_NODES],
    f: [[f64; 3]; 3],
    /// Green–Lagrange strain (small strain: the symmetric gradient).
    e: [[f64; 3]; 3],
    jxw: f64,
    nn: usize,
}

impl ContinuumKernel<'_> {
    /// A point law of the strain: σ(ε), or S(E) with the geometric stiffness.
    #[allow(clippy::too_many_arguments)]
    fn linear_point(
        &self,
        law: &dyn PointLaw,
        (old, new): (&[f64], &mut [f64]),
        pt: &Point,
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        b: &mut [[f64; MAX_DOFS]; 6],
        states: Option<&mut Vec<GpState>>,
    ) {
        let (nsd, nn, jxw, dndx, f, e) = (self.nsd, pt.nn, pt.jxw, pt.dndx, pt.f, pt.e);
        let ndof = nn * nsd;
        let nc = law.components();
        let comps = voigt_components_of(nc);
        let mut strain = [0.0; 6];
        for (k, &c) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[c];
            strain[k] = if i == j { e[i][j] } else { 2.0 * e[i][j] };
        }
        let (mut sv, mut d) = ([0.0; 6], [0.0; 36]);
        law.respond(&strain[..nc], old, &mut sv[..nc], &mut d[..nc * nc], new);
        let mut s = [[0.0; 3]; 3];
        for (k, &c) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[c];
            s[i][j] = sv[k];
            s[j][i] = sv[k];
        }
        let fm = if self.nlgeo {
            f
        } else {
            [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        };
        // Internal force f_ai = ∫ F_iI S_IJ ∂N_a/∂X_J.
        let mut fs = [[0.0; 3]; 3];
        for i in 0..nsd {
            for jj in 0..nsd {
                fs[i][jj] = (0..nsd).map(|ii| fm[i][ii] * s[ii][jj]).sum();
            }
        }
        for a in 0..nn {
            for i in 0..nsd {
                fe[a * nsd + i] += jxw * (0..nsd).map(|jj| fs[i][jj] * dndx[a][jj]).sum::<f64>();
            }
        }
        if let Some(k) = ke {
            // B rows: δE_k = B_k · δu.
            for (row, &c) in comps.iter().enumerate() {
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
            let mut db = [[0.0; MAX_DOFS]; 6];
            for r in 0..nc {
                for q in 0..ndof {
                    db[r][q] = (0..nc).map(|t| d[r * nc + t] * b[t][q]).sum::<f64>() * jxw;
                }
            }
            for p in 0..ndof {
                for q in 0..ndof {
                    let mut v = 0.0;
                    for r in 0..nc {
                        v += b[r][p] * db[r][q];
                    }
                    k[p * ndof + q] += v;
                }
            }
            if self.nlgeo {
                for a in 0..nn {
                    for bb in 0..nn {
                        let mut gab = 0.0;
                        for ii in 0..nsd {
                            for jj in 0..nsd {
                                gab += dndx[a][ii] * s[ii][jj] * dndx[bb][jj];
                            }
                        }
                        for i in 0..nsd {
                            k[(a * nsd + i) * ndof + bb * nsd + i] += jxw * gab;
                        }
                    }
                }
            }
        }
        if let Some(st) = states {
            let mut full_e = [0.0; 6];
            let mut full_s = [0.0; 6];
            for (k, &c) in comps.iter().enumerate() {
                full_e[c] = strain[k];
                full_s[c] = sv[k];
            }
            if nc == 4 {
                // Plane strain: ε_zz = 0 whatever the reduced vector carries.
                full_e[2] = 0.0;
            }
            let mut p = [[0.0; 3]; 3];
            for i in 0..3 {
                for j in 0..3 {
                    p[i][j] = (0..3).map(|t| fm[i][t] * s[t][j]).sum();
                }
            }
            st.push(GpState {
                strain: full_e,
                stress: full_s,
                f,
                p,
            });
        }
    }

    /// A hyperelastic law at a point: f_ai = ∫ P_iJ ∂N_a/∂X_J, K = ∫ ∂N_a/∂X_J A_iJkL ∂N_b/∂X_L.
    fn hyperelastic_point(
        &self,
        h: &Hyperelastic,
        pt: &Point,
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        states: Option<&mut Vec<GpState>>,
    ) -> Result<(), String> {
        let (nsd, nn, jxw, dndx, f) = (self.nsd, pt.nn, pt.jxw, pt.dndx, pt.f);
        let ndof = nn * nsd;
        let (p, mut a) = h
            .pk1(&f)
            .map_err(|det| format!("element inverted (det F = {det:.3e})"))?;
        if matches!(self.material, Constitutive::HyperPlaneStress(_)) {
            // F₃₃ follows the in-plane F through P₃₃ = 0: dF₃₃ = −A₃₃kL dF_kL / A₃₃₃₃, so the
            // in-plane tangent is A_iJkL − A_iJ33 A_33kL / A₃₃₃₃.
            let a33 = a[2][2][2][2];
            let col: [[f64; 2]; 2] =
                std::array::from_fn(|i| std::array::from_fn(|j| a[i][j][2][2]));
            let row: [[f64; 2]; 2] =
                std::array::from_fn(|k| std::array::from_fn(|l| a[2][2][k][l]));
            for i in 0..2 {
                for j in 0..2 {
                    for k in 0..2 {
                        for l in 0..2 {
                            a[i][j][k][l] -= col[i][j] * row[k][l] / a33;
                        }
                    }
                }
            }
        }
        for n in 0..nn {
            for i in 0..nsd {
                fe[n * nsd + i] += jxw * (0..nsd).map(|jj| p[i][jj] * dndx[n][jj]).sum::<f64>();
            }
        }
        if let Some(k) = ke {
            for na in 0..nn {
                for i in 0..nsd {
                    for nb in 0..nn {
                        for kk in 0..nsd {
                            let mut v = 0.0;
                            for jj in 0..nsd {
                                for ll in 0..nsd {
                                    v += dndx[na][jj] * a[i][jj][kk][ll] * dndx[nb][ll];
                                }
                            }
                            k[(na * nsd + i) * ndof + nb * nsd + kk] += jxw * v;
                        }
                    }
                }
            }
        }
        if let Some(st) = states {
            // Green–Lagrange strain and S = F⁻¹P in Voigt form (engineering shear strains).
            let fi = inverse3(&f, det3(&f));
            let mut strain = [0.0; 6];
            let mut stress = [0.0; 6];
            for (c, &(i, j)) in VOIGT_PAIRS.iter().enumerate() {
                strain[c] = if i == j { pt.e[i][j] } else { 2.0 * pt.e[i][j] };
                stress[c] = (0..3).map(|m| fi[i][m] * p[m][j]).sum();
            }
            st.push(GpState {
                strain,
                stress,
                f,
                p,
            });
        }
        Ok(())
    }
}
