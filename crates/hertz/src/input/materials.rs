//! The material block: one record per material, its keyword and parameters.

use super::cursor::{Block, Cursor, Numbered};
use super::record::Record;
use crate::error::Result;
use crate::model::*;

/// The material records; `dynamic`: the analysis needs mass, so a density `d` > 0.
pub(super) fn read_materials(c: &mut Cursor, nmat: usize, dynamic: bool) -> Result<Vec<Material>> {
    let mut mats = Numbered::new("material", nmat);
    for i in 0..nmat {
        let r = c.next_of(Block::Material, i, nmat)?;
        let m = if r.keyword() == "dummymat" {
            Material {
                density: 0.0,
                talpha: 0.0,
                law: MaterialLaw::Dummy,
            }
        } else {
            read_material(&r)?
        };
        if dynamic && !matches!(m.law, MaterialLaw::Dummy) && !(m.density > 0.0) {
            return Err(r.error(format!(
                "a dynamic analysis needs mass: the density `d` must be positive, found {}",
                m.density
            )));
        }
        mats.put(&r, m)?;
        c.finish(&r);
    }
    let materials = mats.finish();

    Ok(materials)
}

/// A material record: `IsoLE`, or one of upstream OOFEM's compressible hyperelastic laws.
pub(super) fn read_material(r: &Record) -> Result<Material> {
    let density = r.float("d")?;
    let talpha = r.opt_float("talpha")?.unwrap_or(0.0);
    r.opt_float("referencetemperature")?;
    // A modulus below the smallest normal double (a subnormal, 1e-320) loses its digits in
    // every product: the stiffness underflows and the solver would report a mechanism.
    let positive = |key: &str, v: f64| -> Result<f64> {
        if v >= f64::MIN_POSITIVE {
            Ok(v)
        } else if v > 0.0 {
            Err(r.error(format!(
                "`{key}` {v:e} is below the smallest normal double (2.2e-308): the stiffness \
                 would underflow; give the moduli in other units"
            )))
        } else {
            Err(r.error(format!("`{key}` must be positive, found {v}")))
        }
    };
    let law = match r.keyword() {
        "isole" => {
            let young = r.float("e")?;
            let poisson = r.float("n")?;
            r.float("talpha")?;
            if !(young > 0.0) {
                return Err(r.error(format!("Young's modulus E must be positive, found {young}")));
            }
            positive("E", young)?;
            if !(poisson > -1.0 && poisson < 0.5) {
                return Err(r.error(format!(
                    "Poisson's ratio n must lie in (-1, 0.5), found {poisson}"
                )));
            }
            MaterialLaw::LinearElastic { young, poisson }
        }
        "misesmat" => MaterialLaw::Mises(read_mises(r, &positive)?),
        "mooneyrivlincompressiblemat" => {
            let (c1, c2) = (r.float("c1")?, r.float("c2")?);
            let k = positive("k", r.float("k")?)?;
            if !(c1 + c2 > 0.0) {
                return Err(r.error(format!(
                    "the shear modulus 2(c1 + c2) must be positive, found {}",
                    2.0 * (c1 + c2)
                )));
            }
            MaterialLaw::MooneyRivlin { c1, c2, k }
        }
        "ogdencompressiblemat" => {
            let alpha = r.float_array("alpha")?;
            let mu = r.float_array("mu")?;
            let k = positive("k", r.float("k")?)?;
            if alpha.is_empty() || alpha.len() != mu.len() || alpha.len() > 7 {
                return Err(r.error(format!(
                    "`alpha` and `mu` need the same number of terms, 1 to 7 (found {} and {})",
                    alpha.len(),
                    mu.len()
                )));
            }
            if alpha.iter().any(|a| !(a.abs() > 0.0)) {
                return Err(r.error("every `alpha` must be non-zero"));
            }
            let g = 0.5 * alpha.iter().zip(&mu).map(|(a, m)| a * m).sum::<f64>();
            if !(g > 0.0) {
                return Err(r.error(format!(
                    "the shear modulus ½ Σ alpha·mu must be positive, found {g}"
                )));
            }
            MaterialLaw::Ogden { alpha, mu, k }
        }
        "simopistermat" => MaterialLaw::SimoPister {
            g: positive("g", r.float("g")?)?,
            k: positive("k", r.float("k")?)?,
        },
        other => {
            return Err(r.error(format!(
                "unsupported material `{other}`; supported: IsoLE, MisesMat, \
                 MooneyRivlinCompressibleMat, OgdenCompressibleMat, SimoPisterMat (or is a count \
                 before nmat wrong?)"
            )))
        }
    };
    Ok(Material {
        density,
        talpha,
        law,
    })
}

/// `MisesMat`: isotropic elasticity (`E`, `n`), the yield stress by `htype` (0: `sig0` and `H`;
/// 1: the table `h_eps`, `h(eps)`), damage (`omega_crit`, `a`) and, a hertz extension, linear
/// kinematic hardening `hk`.
fn read_mises(r: &Record, positive: &dyn Fn(&str, f64) -> Result<f64>) -> Result<Mises> {
    let young = positive("E", r.float("e")?)?;
    let poisson = r.float("n")?;
    if !(poisson > -1.0 && poisson < 0.5) {
        return Err(r.error(format!(
            "Poisson's ratio n must lie in (-1, 0.5), found {poisson}"
        )));
    }
    r.opt_float("talpha")?;
    // OOFEM's tolerance of its plane-stress return; hertz's returns are exact to round-off.
    r.opt_float("yieldtol")?;
    let hardening = match r.opt_int("htype")?.unwrap_or(0) {
        0 => Hardening::Linear {
            sig0: positive("sig0", r.float("sig0")?)?,
            modulus: r.opt_float("h")?.unwrap_or(0.0),
        },
        1 => {
            let kappa = r.float_array("h_eps")?;
            let stress = r.float_array("h(eps)")?;
            if kappa.len() != stress.len() || kappa.is_empty() {
                return Err(r.error(format!(
                    "`h_eps` and `h(eps)` need the same number of points, at least one (found {} \
                     and {})",
                    kappa.len(),
                    stress.len()
                )));
            }
            if kappa[0] != 0.0 {
                return Err(r.error(format!(
                    "the first point of `h_eps` must be 0, found {}",
                    kappa[0]
                )));
            }
            if kappa.windows(2).any(|w| !(w[1] > w[0])) {
                return Err(r.error("the points of `h_eps` must increase"));
            }
            if stress.iter().any(|s| !(*s > 0.0)) {
                return Err(r.error("every yield stress of `h(eps)` must be positive"));
            }
            Hardening::Table { kappa, stress }
        }
        other => {
            return Err(r.error(format!(
                "`htype {other}` is not a hardening type: 0 (sig0, H) or 1 (h_eps, h(eps))"
            )))
        }
    };
    let kinematic = r.opt_float("hk")?.unwrap_or(0.0);
    if !(kinematic >= 0.0) {
        return Err(r.error(format!(
            "the kinematic hardening modulus hk must not be negative, found {kinematic}"
        )));
    }
    let critical = r.opt_float("omega_crit")?.unwrap_or(0.0);
    let rate = r.opt_float("a")?.unwrap_or(0.0);
    if !(0.0..1.0).contains(&critical) || !(rate >= 0.0) {
        return Err(r.error(format!(
            "damage needs 0 ≤ omega_crit < 1 and a ≥ 0, found omega_crit {critical}, a {rate}"
        )));
    }
    Ok(Mises {
        young,
        poisson,
        hardening,
        kinematic,
        damage: (critical > 0.0 && rate > 0.0).then_some(Damage { critical, rate }),
    })
}
