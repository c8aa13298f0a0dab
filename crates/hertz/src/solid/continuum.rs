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

/// Maximum nodes and DOFs per element.
pub use crate::fem::MAX_NODES;
pub const MAX_DOFS: usize = 3 * MAX_NODES;

/// Everything a continuum kernel needs besides nodal data.
pub struct ContinuumKernel<'a> {
    pub shape: Shape,
    pub nsd: usize,
    pub rule: &'a [QuadPoint],
    pub material: &'a dyn PointLaw,
    /// Thickness for 2D elements (1 in 3D).
    pub thick: f64,
    pub nlgeo: bool,
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
            self.point(
                (&old[g * sl..(g + 1) * sl], &mut new[g * sl..(g + 1) * sl]),
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
    /// The material's response at a point: σ(ε), or S(E) with the geometric stiffness.
    fn point(
        &self,
        (old, new): (&[f64], &mut [f64]),
        pt: &Point,
        fe: &mut [f64],
        ke: Option<&mut [f64]>,
        (b, db): (&mut [[f64; MAX_DOFS]; 6], &mut [[f64; MAX_DOFS]; 6]),
        states: Option<&mut Vec<GpState>>,
    ) -> Result<(), String> {
        let law = self.material;
        let (nsd, nn, jxw, dndx, mut f, e) = (self.nsd, pt.nn, pt.jxw, pt.dndx, pt.f, pt.e);
        let ndof = nn * nsd;
        let nc = law.components();
        let comps = voigt_components_of(nc);
        let mut strain = [0.0; 6];
        for (k, &c) in comps.iter().enumerate() {
            let (i, j) = VOIGT_PAIRS[c];
            strain[k] = if i == j { e[i][j] } else { 2.0 * e[i][j] };
        }
        let (mut sv, mut d) = ([0.0; 6], [0.0; 36]);
        let mut out = Response {
            stress: &mut sv[..nc],
            tangent: &mut d[..nc * nc],
            state: new,
            normal_strain: 0.0,
        };
        law.respond(&strain[..nc], old, &mut out)?;
        let normal_strain = out.normal_strain;
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
            // The rows of B that can be non-zero: in 2D not those of a component with z (the
            // plane-strain ε_zz, whose row vanishes).
            let mut rows = [0usize; 6];
            let mut nr = 0;
            for (row, &c) in comps.iter().enumerate() {
                let (ii, jj) = VOIGT_PAIRS[c];
                if ii < nsd && jj < nsd {
                    rows[nr] = row;
                    nr += 1;
                }
            }
            let rows = &rows[..nr];
            for &r in rows {
                for q in 0..ndof {
                    db[r][q] = rows.iter().map(|&t| d[r * nc + t] * b[t][q]).sum::<f64>() * jxw;
                }
            }
            // Bᵀ D B, one triangle mirrored where D is symmetric.
            let symmetric = law.symmetric_tangent();
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
            if nc == 3 && normal_strain != 0.0 {
                // Plane stress: the normal strain the law found, and its stretch in F.
                full_e[2] = normal_strain;
                if self.nlgeo {
                    f[2][2] = (1.0 + 2.0 * normal_strain).sqrt();
                }
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
        Ok(())
    }
}
