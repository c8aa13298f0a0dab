//! Geometry maps from the reference element (no physics): Jacobians and ∂N/∂X.

/// Compute ∂N/∂X from ∂N/∂ξ for the reference geometry; returns det J (None if zero).
pub fn map_derivatives(
    nsd: usize,
    nn: usize,
    x: &[[f64; 3]],
    dn: &[[f64; 3]],
    dndx: &mut [[f64; 3]],
) -> Option<f64> {
    let mut j = [[0.0; 3]; 3];
    for a in 0..nn {
        for i in 0..nsd {
            for k in 0..nsd {
                j[i][k] += x[a][i] * dn[a][k];
            }
        }
    }
    if nsd == 2 {
        j[2][2] = 1.0;
    }
    let det = det3(&j);
    if det.abs() < 1e-300 || !det.is_finite() {
        return None;
    }
    let inv = inverse3(&j, det);
    for a in 0..nn {
        for i in 0..3 {
            dndx[a][i] = if i < nsd {
                (0..nsd).map(|k| dn[a][k] * inv[k][i]).sum()
            } else {
                0.0
            };
        }
    }
    Some(det)
}

pub fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

pub fn inverse3(m: &[[f64; 3]; 3], det: f64) -> [[f64; 3]; 3] {
    let mut r = [[0.0; 3]; 3];
    r[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / det;
    r[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
    r[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
    r[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
    r[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
    r[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
    r[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
    r[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
    r[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
    r
}

/// det J of the reference map at every point of `rule`, for an element with node coordinates `x`.
pub fn jacobian_dets(shape: super::Shape, x: &[[f64; 3]], rule: &[super::QuadPoint]) -> Vec<f64> {
    let nn = shape.n_nodes();
    let mut n = [0.0; super::MAX_NODES];
    let mut dn = [[0.0; 3]; super::MAX_NODES];
    let mut dndx = [[0.0; 3]; super::MAX_NODES];
    rule.iter()
        .map(|q| {
            shape.eval(q.xi, &mut n, &mut dn);
            map_derivatives(shape.dim(), nn, x, &dn, &mut dndx).unwrap_or(0.0)
        })
        .collect()
}

/// det J at the centre of the reference element: its sign is the element's orientation.
pub fn det_j_at_centre(shape: super::Shape, x: &[[f64; 3]]) -> f64 {
    let centre = super::QuadPoint {
        xi: shape.centre(),
        weight: 1.0,
    };
    jacobian_dets(shape, x, &[centre])[0]
}
