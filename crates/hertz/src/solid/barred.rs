//! The barred linear elements (OOFEM's `LSpaceBB`, hertz's `Quad1PlaneStrainBB`): the
//! volumetric deformation of every integration point is the element's mean, so a linear
//! quadrilateral or brick does not lock where the material is (nearly) incompressible —
//! plastic flow, rubber.
//!
//! Small strain (B-bar): ε̄ = ε + ⅓(θ̄ − θ)·I, θ = tr ε at the point, θ̄ its mean over the
//! element (mean dilatation); the continuum kernel adds it to the strain, B̄ᵀσ to the forces
//! and B̄ to the tangent. OOFEM's `LSpaceBB` takes θ at the centre instead: the same on a
//! parallelepiped, but on a distorted brick ∫∇N dV ≠ V·∇N(centre), and a homogeneous stress
//! then gives wrong nodal forces (its patch test fails: QUIRK). Large deformation (F-bar; de
//! Souza Neto, Perić, Dunne & Owen 1996, with the mean dilatation J̄ = v/V of Simo, Taylor &
//! Pister 1985 for the same reason, in the total Lagrangian form): F̄ = α·F with
//! α = (J̄/J)^(1/n) over the n in-plane dimensions, the law's S̄(Ē) at Ē = ½(F̄ᵀF̄ − I), the
//! forces ∫ S̄ : ∂Ē/∂u and the exact tangent ∫ ∂Ē/∂u : D : ∂Ē/∂u + S̄ : ∂²Ē/∂u² (OOFEM's
//! `LSpaceBB` is a plain `LSpace` in large deformation).

use super::kernel::{GpState, KernelError};
use crate::fem::geometry::{det3, inverse3, map_derivatives};
use crate::fem::{QuadPoint, Shape, MAX_DOFS, MAX_NODES};
use crate::material::{voigt_components_of, PointLaw, Response, VOIGT_PAIRS};

type M3 = [[f64; 3]; 3];

/// The element's means: of ∂N_a/∂X (small strain: θ̄ = Σ u·that), and of J (J̄ = v/V) with its
/// first and second derivatives over the element's DOFs (large deformation).
pub struct Means {
    pub dndx: [[f64; 3]; MAX_NODES],
    pub theta: f64,
    pub j: f64,
    pub dj: Vec<f64>,
    pub ddj: Vec<f64>,
}

/// Kinematics at one integration point of an F-bar element of dimension `nsd`.
pub struct FbarPoint<'a> {
    pub nsd: usize,
    pub dndx: &'a [[f64; 3]; MAX_NODES],
    pub f: M3,
    pub jxw: f64,
    pub nn: usize,
}

/// F = I + ∂u/∂X at a point (F₃₃ = 1 in 2D).
fn deformation_gradient(dndx: &[[f64; 3]; MAX_NODES], u: &[f64], nn: usize, nsd: usize) -> M3 {
    let mut f = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for a in 0..nn {
        for i in 0..nsd {
            for j in 0..nsd {
                f[i][j] += u[a * nsd + i] * dndx[a][j];
            }
        }
    }
    f
}

/// The part of a DOF p = (a, i) a derivative takes: F_p = e_i ⊗ ∇N_a.
fn grad_n(dndx: &[[f64; 3]; MAX_NODES], p: usize, nsd: usize) -> (usize, [f64; 3]) {
    (p % nsd, dndx[p / nsd])
}

/// The means over the integration points `rule` of an element of `shape` in `nsd` dimensions
/// at reference coordinates `x_ref` and displacements `u`: ∂N_a/∂X and θ̄; with `nlgeo`, J̄
/// and ∂J̄/∂u_p = ⟨J G_a,i⟩, ∂²J̄/∂u_p∂u_q = ⟨J (G_a,i G_b,k − G_b,i G_a,k)⟩ (p = (a, i),
/// q = (b, k), G_a = F⁻ᵀ∇N_a, ⟨·⟩ the mean over the reference volume).
pub fn means(
    (shape, nsd, rule): (Shape, usize, &[QuadPoint]),
    nlgeo: bool,
    x_ref: &[[f64; 3]],
    u: &[f64],
) -> Result<Means, KernelError> {
    let nn = shape.n_nodes();
    let ndof = nn * nsd;
    let mut n = [0.0; MAX_NODES];
    let mut dn = [[0.0; 3]; MAX_NODES];
    let mut dndx = [[0.0; 3]; MAX_NODES];
    let mut c = Means {
        dndx: [[0.0; 3]; MAX_NODES],
        theta: 0.0,
        j: 0.0,
        dj: vec![0.0; if nlgeo { ndof } else { 0 }],
        ddj: vec![0.0; if nlgeo { ndof * ndof } else { 0 }],
    };
    let mut volume = 0.0;
    for (g, qp) in rule.iter().enumerate() {
        shape.eval(qp.xi, &mut n, &mut dn);
        let det = map_derivatives(nsd, nn, x_ref, &dn, &mut dndx).ok_or_else(|| KernelError {
            gp: g + 1,
            msg: "degenerate element geometry (det J = 0)".into(),
        })?;
        let w = det.abs() * qp.weight;
        volume += w;
        for a in 0..nn {
            for i in 0..nsd {
                c.dndx[a][i] += w * dndx[a][i];
            }
        }
        if !nlgeo {
            continue;
        }
        let f = deformation_gradient(&dndx, u, nn, nsd);
        let j = det3(&f);
        if j <= 0.0 {
            return Err(KernelError {
                gp: g + 1,
                msg: format!("element inverted (det F = {j:.3e})"),
            });
        }
        let fi = inverse3(&f, j);
        let big_g = |a: usize, i: usize| (0..nsd).map(|k| fi[k][i] * dndx[a][k]).sum::<f64>();
        c.j += w * j;
        for p in 0..ndof {
            let (a, i) = (p / nsd, p % nsd);
            c.dj[p] += w * j * big_g(a, i);
            for q in 0..ndof {
                let (b, k) = (q / nsd, q % nsd);
                c.ddj[p * ndof + q] +=
                    w * j * (big_g(a, i) * big_g(b, k) - big_g(b, i) * big_g(a, k));
            }
        }
    }
    for a in 0..nn {
        for i in 0..nsd {
            c.dndx[a][i] /= volume;
            c.theta += u[a * nsd + i] * c.dndx[a][i];
        }
    }
    c.j /= volume;
    c.dj.iter_mut().for_each(|v| *v /= volume);
    c.ddj.iter_mut().for_each(|v| *v /= volume);
    Ok(c)
}

/// One F-bar point of the law `law`: the law at Ē, its forces and tangent (see the module's
/// text).
pub fn fbar_point(
    law: &dyn PointLaw,
    c: &Means,
    pt: &FbarPoint,
    (old, new): (&[f64], &mut [f64]),
    fe: &mut [f64],
    ke: Option<&mut [f64]>,
    states: Option<&mut Vec<GpState>>,
) -> Result<(), String> {
    let nsd = pt.nsd;
    let ndof = pt.nn * nsd;
    let nd = nsd as f64;
    let j = det3(&pt.f);
    let fi = inverse3(&pt.f, j);
    let alpha = (c.j / j).powf(1.0 / nd);
    let cc = mul_tn(&pt.f, &pt.f);
    // Ē = ½(α²C − I) in the plane (Ē_zz = 0 in 2D: F̄₃₃ = 1).
    let mut e = [[0.0; 3]; 3];
    for i in 0..nsd {
        for k in 0..nsd {
            e[i][k] = 0.5 * (alpha * alpha * cc[i][k] - if i == k { 1.0 } else { 0.0 });
        }
    }
    let nc = law.components();
    let comps = voigt_components_of(nc);
    let strain: Vec<f64> = comps
        .iter()
        .map(|&k| {
            let (a, b) = VOIGT_PAIRS[k];
            if a == b {
                e[a][b]
            } else {
                2.0 * e[a][b]
            }
        })
        .collect();
    let (mut stress, mut d) = ([0.0; 6], [0.0; 36]);
    let mut out = Response {
        stress: &mut stress[..nc],
        tangent: &mut d[..nc * nc],
        state: new,
        normal_strain: 0.0,
    };
    law.respond(&strain, old, &mut out)?;
    let mut s = [[0.0; 3]; 3];
    for (k, &cmp) in comps.iter().enumerate() {
        let (a, b) = VOIGT_PAIRS[cmp];
        s[a][b] = stress[k];
        s[b][a] = stress[k];
    }
    // g_p = ∂ ln α/∂u_p = (1/n)(∂J̄/∂u_p / J̄ − G_a,i).
    let g_of = |p: usize| {
        let (i, n) = grad_n(pt.dndx, p, nsd);
        let t: f64 = (0..nsd).map(|k| fi[k][i] * n[k]).sum();
        (c.dj[p] / c.j - t) / nd
    };
    let g: Vec<f64> = (0..ndof).map(g_of).collect();
    // E_p = α² sym(FᵀF_p) + α α_p C, in the plane.
    let mut ep = vec![[[0.0; 3]; 3]; ndof];
    for (p, epp) in ep.iter_mut().enumerate() {
        let (i, n) = grad_n(pt.dndx, p, nsd);
        for a in 0..nsd {
            for b in 0..nsd {
                let sym = 0.5 * (pt.f[i][a] * n[b] + pt.f[i][b] * n[a]);
                epp[a][b] = alpha * alpha * (sym + g[p] * cc[a][b]);
            }
        }
    }
    for p in 0..ndof {
        fe[p] += pt.jxw * contract(&s, &ep[p]);
    }
    if let Some(k) = ke {
        fbar_tangent(c, pt, (&s, &d[..nc * nc], comps), (alpha, &g, &ep), &fi, k);
    }
    if let Some(st) = states {
        let mut fbar = pt.f;
        for row in fbar.iter_mut().take(nsd) {
            for x in row.iter_mut().take(nsd) {
                *x *= alpha;
            }
        }
        let mut state = GpState::default();
        for (k, &cmp) in comps.iter().enumerate() {
            state.stress[cmp] = stress[k];
            state.strain[cmp] = strain[k];
        }
        state.f = fbar;
        for a in 0..3 {
            for b in 0..3 {
                state.p[a][b] = (0..3).map(|t| fbar[a][t] * s[t][b]).sum();
            }
        }
        state.plastic = law.plastic(new);
        st.push(state);
    }
    Ok(())
}

/// k += ∫ E_p : D : E_q + S̄ : E_pq, with α_p = α g_p, α_pq = α(g_p g_q + g_pq),
/// E_pq = α² sym(F_qᵀF_p) + 2αα_q sym(FᵀF_p) + 2αα_p sym(FᵀF_q) + (α_pα_q + αα_pq) C
/// = α²(sym(F_qᵀF_p) + 2g_q sym(FᵀF_p) + 2g_p sym(FᵀF_q) + (2g_p g_q + g_pq) C) and
/// g_pq = (1/n)(J̄_pq/J̄ − J̄_p J̄_q/J̄² + G_b,i G_a,k) for p = (a, i), q = (b, k),
/// G_a = F⁻ᵀ∇N_a (∂² ln J/∂u_p∂u_q = −G_b,i G_a,k).
fn fbar_tangent(
    c: &Means,
    pt: &FbarPoint,
    (s, d, comps): (&M3, &[f64], &[usize]),
    (alpha, g, ep): (f64, &[f64], &[M3]),
    fi: &M3,
    k: &mut [f64],
) {
    let nsd = pt.nsd;
    let ndof = pt.nn * nsd;
    let nd = nsd as f64;
    let nc = comps.len();
    let cc = mul_tn(&pt.f, &pt.f);
    // G_a = F⁻ᵀ∇N_a.
    let big_g: Vec<[f64; 3]> = (0..pt.nn)
        .map(|a| std::array::from_fn(|i| (0..nsd).map(|kk| fi[kk][i] * pt.dndx[a][kk]).sum()))
        .collect();
    // E_p in the law's Voigt components (engineering shears), and D·E_q.
    let mut ev = [[0.0; 6]; MAX_DOFS];
    for p in 0..ndof {
        for (r, &cmp) in comps.iter().enumerate() {
            let (a, b) = VOIGT_PAIRS[cmp];
            ev[p][r] = if a == b {
                ep[p][a][b]
            } else {
                2.0 * ep[p][a][b]
            };
        }
    }
    // S̄ : sym(FᵀF_p) and S̄ : C, in the plane.
    let s_c: f64 = (0..nsd)
        .flat_map(|a| (0..nsd).map(move |b| (a, b)))
        .map(|(a, b)| s[a][b] * cc[a][b])
        .sum();
    let s_sym: Vec<f64> = (0..ndof)
        .map(|p| {
            let (i, n) = grad_n(pt.dndx, p, nsd);
            let mut v = 0.0;
            for a in 0..nsd {
                for b in 0..nsd {
                    v += s[a][b] * pt.f[i][a] * n[b];
                }
            }
            v
        })
        .collect();
    for p in 0..ndof {
        let (i, n) = grad_n(pt.dndx, p, nsd);
        let a_node = p / nsd;
        for q in 0..ndof {
            let (kq, nq) = grad_n(pt.dndx, q, nsd);
            let b_node = q / nsd;
            // Material: E_p : D : E_q.
            let mut v = 0.0;
            for r in 0..nc {
                for t in 0..nc {
                    v += ev[p][r] * d[r * nc + t] * ev[q][t];
                }
            }
            // S̄ : α² sym(F_qᵀF_p) = α² δ_ik (∇N_a·S̄·∇N_b).
            if i == kq {
                let mut sn = 0.0;
                for a in 0..nsd {
                    for b in 0..nsd {
                        sn += n[a] * s[a][b] * nq[b];
                    }
                }
                v += alpha * alpha * sn;
            }
            let gpq = (c.ddj[p * ndof + q] / c.j - c.dj[p] * c.dj[q] / (c.j * c.j)
                + big_g[b_node][i] * big_g[a_node][kq])
                / nd;
            v += alpha
                * alpha
                * (2.0 * g[q] * s_sym[p] + 2.0 * g[p] * s_sym[q] + (2.0 * g[p] * g[q] + gpq) * s_c);
            k[p * ndof + q] += pt.jxw * v;
        }
    }
}

fn mul_tn(a: &M3, b: &M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|j| (0..3).map(|k| a[k][i] * b[k][j]).sum()))
}

fn contract(a: &M3, b: &M3) -> f64 {
    (0..3)
        .flat_map(|i| (0..3).map(move |j| (i, j)))
        .map(|(i, j)| a[i][j] * b[i][j])
        .sum()
}
