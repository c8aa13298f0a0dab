//! Continuum element kernel for every 2D/3D shape: small strain, or total Lagrangian
//! (`nlgeo 1`: Green–Lagrange strain E = ½(FᵀF − I), S = D:E, consistent tangent with the
//! geometric stiffness).
//!
//! Glossary: `nsd` space dimensions; `x_ref[a]` reference coordinates of node a; `u[a*nsd+i]`
//! displacement; `dndx[a][I]` = ∂N_a/∂X_I; `f` = F (deformation gradient, 3×3, F₃₃ = 1 in 2D);
//! `s` = second Piola–Kirchhoff stress tensor; `jxw` = |det J|·weight·thickness.

use super::material::{Elasticity, VOIGT_PAIRS};
use crate::fem::geometry::{det3, map_derivatives};
use crate::fem::{QuadPoint, Shape};
use crate::model::StressMode;

/// Maximum nodes and DOFs per element.
pub const MAX_NODES: usize = 8;
pub const MAX_DOFS: usize = 24;

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
    pub elasticity: &'a Elasticity,
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

impl ContinuumKernel<'_> {
    /// Internal force `fe` (len nnode·nsd) and, if requested, tangent `ke` (row-major square)
    /// and integration-point states.
    pub fn evaluate_into(
        &self,
        x_ref: &[[f64; 3]],
        u: &[f64],
        fe: &mut [f64],
        mut ke: Option<&mut [f64]>,
        mut states: Option<&mut Vec<GpState>>,
    ) -> Result<(), KernelError> {
        let nsd = self.nsd;
        let nn = self.shape.n_nodes();
        let ndof = nn * nsd;
        fe[..ndof].fill(0.0);
        if let Some(k) = ke.as_deref_mut() {
            k[..ndof * ndof].fill(0.0);
        }
        let el = self.elasticity;
        let comps = super::material::voigt_components(el.mode);
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
            let mut strain = [0.0; 6];
            for (k, &c) in comps.iter().enumerate() {
                let (i, j) = VOIGT_PAIRS[c];
                strain[k] = if i == j { e[i][j] } else { 2.0 * e[i][j] };
            }
            if el.mode == StressMode::PlaneStress {
                // εz is not part of the plane-stress state (OOFEM reports 0).
            }
            let mut sv = [0.0; 6];
            el.stress(&strain[..el.n], &mut sv[..el.n]);
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
                    fe[a * nsd + i] +=
                        jxw * (0..nsd).map(|jj| fs[i][jj] * dndx[a][jj]).sum::<f64>();
                }
            }
            if let Some(k) = ke.as_deref_mut() {
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
                let nc = el.n;
                let mut db = [[0.0; MAX_DOFS]; 6];
                for r in 0..nc {
                    for q in 0..ndof {
                        db[r][q] = (0..nc).map(|t| el.d[r][t] * b[t][q]).sum::<f64>() * jxw;
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
            if let Some(st) = states.as_deref_mut() {
                let mut full_e = [0.0; 6];
                let mut full_s = [0.0; 6];
                for (k, &c) in comps.iter().enumerate() {
                    full_e[c] = strain[k];
                    full_s[c] = sv[k];
                }
                if el.mode == StressMode::PlaneStrain {
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
        Ok(())
    }

    /// ∫ N_a dV for each node (for body forces).
    pub fn integrate_shape(&self, x_ref: &[[f64; 3]], out: &mut [f64]) -> Result<(), KernelError> {
        let nn = self.shape.n_nodes();
        out[..nn].fill(0.0);
        let mut n = [0.0; MAX_NODES];
        let mut dn = [[0.0; 3]; MAX_NODES];
        let mut dndx = [[0.0; 3]; MAX_NODES];
        for (g, qp) in self.rule.iter().enumerate() {
            self.shape.eval(qp.xi, &mut n, &mut dn);
            let det = map_derivatives(self.nsd, nn, x_ref, &dn, &mut dndx).ok_or_else(|| {
                KernelError {
                    gp: g + 1,
                    msg: "degenerate element geometry (det J = 0)".into(),
                }
            })?;
            for a in 0..nn {
                out[a] += n[a] * det.abs() * qp.weight * self.thick;
            }
        }
        Ok(())
    }
}
