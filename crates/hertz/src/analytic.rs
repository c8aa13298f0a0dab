//! Analytical contact solutions and the measurements that compare a computed contact state with
//! them (used by the examples and their tests).

use crate::contact::SlotState;
use crate::model::Model;

/// Plane-strain Hertz contact of cylinders: half-width a = sqrt(4 F R / (π E*)), F per unit length.
pub fn hertz_half_width(force: f64, radius: f64, e_star: f64) -> f64 {
    (4.0 * force * radius / (std::f64::consts::PI * e_star)).sqrt()
}

/// Plane-strain Hertz maximum pressure p0 = sqrt(F E* / (π R)).
pub fn hertz_max_pressure(force: f64, radius: f64, e_star: f64) -> f64 {
    (force * e_star / (std::f64::consts::PI * radius)).sqrt()
}

/// Contact modulus of two bodies: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2 (E2 = ∞ for a rigid body).
pub fn contact_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    let inv2 = if e2.is_finite() {
        (1.0 - nu2 * nu2) / e2
    } else {
        0.0
    };
    1.0 / ((1.0 - nu1 * nu1) / e1 + inv2)
}

/// Hertz contact of spheres: contact radius a = (3 F R / (4 E*))^(1/3).
pub fn hertz_sphere_radius(force: f64, radius: f64, e_star: f64) -> f64 {
    (3.0 * force * radius / (4.0 * e_star)).cbrt()
}

/// Hertz contact of spheres: maximum pressure p0 = 3 F / (2 π a²).
pub fn hertz_sphere_pressure(force: f64, a: f64) -> f64 {
    3.0 * force / (2.0 * std::f64::consts::PI * a * a)
}

/// Compare the contact state of a quarter model (symmetry planes x = 0 and y = 0, contact
/// centred on the z axis) of a sphere of radius `radius` with Hertz's solution for the computed
/// force: p0 is the pressure of the node on the axis, a from the ellipse fitted to the active
/// nodes off the contact's rim (those within the finest node spacing of the outermost active
/// node are left out: their tributary area straddles the edge).
pub fn compare_hertz_sphere(
    model: &Model,
    states: &[SlotState],
    radius: f64,
    e_star: f64,
) -> Option<HertzComparison> {
    let force = 4.0 * states.iter().map(|s| s.force).sum::<f64>();
    let pos = |s: &SlotState| {
        let c = model.nodes[s.node].coords;
        c[0].hypot(c[1])
    };
    let active: Vec<&SlotState> = states.iter().filter(|s| s.active).collect();
    let mut spacing = f64::INFINITY;
    for (i, a) in active.iter().enumerate() {
        let p = model.nodes[a.node].coords;
        for b in &active[i + 1..] {
            let q = model.nodes[b.node].coords;
            spacing = spacing.min((p[0] - q[0]).hypot(p[1] - q[1]));
        }
    }
    let rim = active.iter().map(|s| pos(s)).fold(0.0, f64::max);
    let mut profile: Vec<(f64, f64)> = active
        .iter()
        .map(|s| (pos(s), s.pressure))
        .filter(|&(r, _)| r < rim - 0.99 * spacing)
        .collect();
    profile.sort_by(|a, b| a.0.total_cmp(&b.0));
    if profile.len() < 3 || profile[0].0 > 1e-12 {
        return None;
    }
    let p0 = profile[0].1;
    let a = fit_ellipse(&profile)?;
    let a_ref = hertz_sphere_radius(force, radius, e_star);
    Some(HertzComparison {
        force,
        p0,
        p0_ref: hertz_sphere_pressure(force, a_ref),
        a,
        a_ref,
    })
}

/// Pressure under a rigid flat punch of half-width a pressed by F: F / (π sqrt(a² − x²)).
pub fn flat_punch_pressure(force: f64, a: f64, x: f64) -> f64 {
    force / (std::f64::consts::PI * (a * a - x * x).sqrt())
}

/// Radius of the elastic cylinder in examples/hertz_cylinder.in (tools/gen_contact_examples.py).
pub const EXAMPLE_CYLINDER_RADIUS: f64 = 20.0;

/// Computed against analytical Hertz values.
#[derive(Debug, Clone, Copy)]
pub struct HertzComparison {
    pub force: f64,
    pub p0: f64,
    pub p0_ref: f64,
    pub a: f64,
    pub a_ref: f64,
}

impl HertzComparison {
    pub fn p0_error(&self) -> f64 {
        (self.p0 - self.p0_ref) / self.p0_ref
    }
    pub fn a_error(&self) -> f64 {
        (self.a - self.a_ref) / self.a_ref
    }
}

/// Compare the last contact state of a Hertz half model with the analytical solution for the
/// computed force: radius and E* from the model's rigid circle, or from the two materials of an
/// elastic cylinder of radius `cylinder_radius`.
pub fn compare_hertz(
    model: &Model,
    states: &[SlotState],
    cylinder_radius: f64,
) -> Option<HertzComparison> {
    let m1 = &model.materials[0];
    let (radius, e_star) = match &model.segments.first()?.kind {
        crate::model::SegmentKind::Circle { radius, .. } => (
            *radius,
            contact_modulus(m1.young(), m1.poisson(), f64::INFINITY, 0.0),
        ),
        _ => {
            let m2 = model.materials.get(1)?;
            (
                cylinder_radius,
                contact_modulus(m1.young(), m1.poisson(), m2.young(), m2.poisson()),
            )
        }
    };
    let force = full_contact_force(states);
    let (p0, a) = fit_hertz(&pressure_profile(model, states))?;
    Some(HertzComparison {
        force,
        p0,
        p0_ref: hertz_max_pressure(force, radius, e_star),
        a,
        a_ref: hertz_half_width(force, radius, e_star),
    })
}

/// Contact pressures along x (reference position of the contact node) of the active nodes of a
/// half model (x ≥ 0), sorted by x.
pub fn pressure_profile(model: &Model, states: &[SlotState]) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = states
        .iter()
        .filter(|s| s.active)
        .map(|s| (model.nodes[s.node].coords[0], s.pressure))
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    p
}

/// Total contact force of a half model, doubled: the force of the full contact.
pub fn full_contact_force(states: &[SlotState]) -> f64 {
    2.0 * states.iter().map(|s| s.force).sum::<f64>()
}

/// Measured Hertz parameters: p0 at the symmetry node and the half-width a of the ellipse
/// p² = p0²(1 − x²/a²) fitted (least squares in p² against x²) to the active nodes whose tributary
/// lies inside the contact (all but the outermost).
pub fn fit_hertz(profile: &[(f64, f64)]) -> Option<(f64, f64)> {
    if profile.len() < 4 {
        return None;
    }
    Some((profile[0].1, fit_ellipse(&profile[..profile.len() - 1])?))
}

/// The semi-axis a of the ellipse p² = p0²(1 − x²/a²) fitted to the points (x, p) (least squares
/// in p² against x²).
pub fn fit_ellipse(pts: &[(f64, f64)]) -> Option<f64> {
    let n = pts.len() as f64;
    let (mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0);
    for &(x, p) in pts {
        let (u, v) = (x * x, p * p);
        sx += u;
        sy += v;
        sxx += u * u;
        sxy += u * v;
    }
    let slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    let intercept = (sy - slope * sx) / n;
    if !(slope < 0.0 && intercept > 0.0) {
        return None;
    }
    Some((-intercept / slope).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipse_fit_recovers_an_exact_hertz_profile() {
        let (p0, a) = (50.0, 1.2);
        let prof: Vec<(f64, f64)> = (0..30)
            .map(|i| i as f64 * 0.04)
            .map(|x| (x, p0 * (1.0 - x * x / (a * a)).max(0.0).sqrt()))
            .collect();
        let (q0, qa) = fit_hertz(&prof).unwrap();
        assert!((q0 - p0).abs() < 1e-12 && (qa - a).abs() < 1e-9);
    }
}
