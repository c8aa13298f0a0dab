//! Isotropic linear elasticity in reduced Voigt form (spec §1.12).
//! Full Voigt order [xx, yy, zz, yz, xz, xy], engineering shear strains.

use crate::model::StressMode;

/// Positions of the reduced components in the full 6-component Voigt vector.
pub fn voigt_components(mode: StressMode) -> &'static [usize] {
    match mode {
        StressMode::PlaneStress => &[0, 1, 5],
        StressMode::PlaneStrain => &[0, 1, 2, 5],
        StressMode::ThreeD => &[0, 1, 2, 3, 4, 5],
        StressMode::Uniaxial => &[0],
    }
}

/// The components of the reduced Voigt form with `n` components (1, 3, 4 or 6: uniaxial, plane
/// stress, plane strain, 3D).
pub fn voigt_components_of(n: usize) -> &'static [usize] {
    match n {
        1 => voigt_components(StressMode::Uniaxial),
        3 => voigt_components(StressMode::PlaneStress),
        4 => voigt_components(StressMode::PlaneStrain),
        _ => voigt_components(StressMode::ThreeD),
    }
}

/// Tensor indices (I, J) of each full Voigt component.
pub const VOIGT_PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)];

/// The reduced elastic stiffness D (row-major, n × n) for a stress mode.
#[derive(Debug, Clone)]
pub struct Elasticity {
    pub mode: StressMode,
    pub n: usize,
    pub d: [[f64; 6]; 6],
}

impl Elasticity {
    pub fn new(e: f64, nu: f64, mode: StressMode) -> Elasticity {
        let mut d = [[0.0; 6]; 6];
        let comps = voigt_components(mode);
        match mode {
            StressMode::Uniaxial => d[0][0] = e,
            StressMode::PlaneStress => {
                let c = e / (1.0 - nu * nu);
                d[0][0] = c;
                d[1][1] = c;
                d[0][1] = c * nu;
                d[1][0] = c * nu;
                d[2][2] = c * (1.0 - nu) / 2.0;
            }
            StressMode::PlaneStrain | StressMode::ThreeD => {
                let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
                let g = e / (2.0 * (1.0 + nu));
                let mut full = [[0.0; 6]; 6];
                for i in 0..3 {
                    for j in 0..3 {
                        full[i][j] = lambda;
                    }
                    full[i][i] = lambda + 2.0 * g;
                    full[i + 3][i + 3] = g;
                }
                for (a, &ca) in comps.iter().enumerate() {
                    for (b, &cb) in comps.iter().enumerate() {
                        d[a][b] = full[ca][cb];
                    }
                }
            }
        }
        Elasticity {
            mode,
            n: comps.len(),
            d,
        }
    }

    /// stress = D · strain (reduced vectors).
    pub fn stress(&self, strain: &[f64], stress: &mut [f64]) {
        for i in 0..self.n {
            stress[i] = (0..self.n).map(|j| self.d[i][j] * strain[j]).sum();
        }
    }
}

impl super::law::PointLaw for Elasticity {
    fn components(&self) -> usize {
        self.n
    }

    fn respond(
        &self,
        strain: &[f64],
        _old: &[f64],
        out: &mut super::law::Response,
    ) -> Result<(), String> {
        self.stress(strain, out.stress);
        for i in 0..self.n {
            for j in 0..self.n {
                out.tangent[i * self.n + j] = self.d[i][j];
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_strain_gives_sigma_z_from_poisson_effect() {
        let el = Elasticity::new(10.0, 0.2, StressMode::PlaneStrain);
        let mut s = [0.0; 4];
        el.stress(&[1e-3, 0.0, 0.0, 0.0], &mut s);
        // σz = ν/(1−ν) σx under εy = εz = 0.
        assert!((s[2] - 0.25 * s[0]).abs() < 1e-15);
        assert!((s[1] - s[2]).abs() < 1e-15);
    }
}
