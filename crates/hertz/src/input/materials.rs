//! The material block: one record per material, its keyword and parameters.

use super::cursor::{Block, Cursor, Numbered};
use super::record::Record;
use crate::error::Result;
use crate::model::*;

pub(super) const MATERIAL_KEYWORDS: [&str; 5] = [
    "isole",
    "misesmat",
    "mooneyrivlincompressiblemat",
    "ogdencompressiblemat",
    "simopistermat",
];

/// The material records.
pub(super) fn read_materials(c: &mut Cursor, nmat: usize) -> Result<Vec<Material>> {
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
    let positive = |key: &str, v: f64| -> Result<f64> {
        if v > 0.0 {
            Ok(v)
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
            if !(poisson > -1.0 && poisson < 0.5) {
                return Err(r.error(format!(
                    "Poisson's ratio n must lie in (-1, 0.5), found {poisson}"
                )));
            }
            MaterialLaw::LinearElastic { young, poisson }
        }
        "misesmat" => {
            let young = positive("E", r.float("e")?)?;
            let poisson = r.float("n")?;
            r.opt_float("talpha")?;
            let yield_stress = positive("sig0", r.float("sig0")?)?;
            let hardening = r.opt_float("h")?.unwrap_or(0.0);
            if !(hardening >= 0.0) {
                return Err(r.error(format!(
                    "the hardening modulus H must not be negative, found {hardening}"
                )));
            }
            for (key, what) in [
                ("omega_crit", "damage"),
                ("siginf", "saturation hardening"),
                ("kappa1", "piecewise hardening"),
            ] {
                if r.opt_float(key)?.is_some_and(|v| v != 0.0) {
                    return Err(r.error(format!(
                        "`{key}` ({what}) is not supported: MisesMat here has linear isotropic \
                         hardening only (sig0, H)"
                    )));
                }
            }
            r.opt_float("a")?;
            MaterialLaw::Mises {
                young,
                poisson,
                yield_stress,
                hardening,
            }
        }
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
                "unsupported material `{other}`; supported: IsoLE, MisesMat (bars), \
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
