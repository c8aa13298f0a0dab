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

/// The reference coordinates ξ of the point `p` in an element of shape `shape` with node
/// coordinates `x` (its isoparametric map inverted by Newton's method from the centre), or None
/// where the map is singular or Newton does not settle (a point far outside a curved element).
pub fn locate(shape: super::Shape, x: &[[f64; 3]], p: [f64; 3]) -> Option<[f64; 3]> {
    let (nn, dim) = (shape.n_nodes(), shape.dim());
    let mut n = [0.0; super::MAX_NODES];
    let mut dn = [[0.0; 3]; super::MAX_NODES];
    let mut xi = shape.centre();
    for _ in 0..30 {
        shape.eval(xi, &mut n, &mut dn);
        let mut r = [0.0; 3];
        let mut j = [[0.0; 3]; 3];
        r[..dim].copy_from_slice(&p[..dim]);
        for i in dim..3 {
            j[i][i] = 1.0;
        }
        for a in 0..nn {
            for i in 0..dim {
                r[i] -= n[a] * x[a][i];
                for k in 0..dim {
                    j[i][k] += x[a][i] * dn[a][k];
                }
            }
        }
        let det = det3(&j);
        if det.abs() < 1e-300 || !det.is_finite() {
            return None;
        }
        let inv = inverse3(&j, det);
        let mut step = [0.0; 3];
        for (k, s) in step.iter_mut().enumerate().take(dim) {
            *s = (0..dim).map(|i| inv[k][i] * r[i]).sum();
        }
        // A step longer than the reference element says only "far outside": shortened to it.
        let len = step.iter().map(|s| s * s).sum::<f64>().sqrt();
        let scale = (2.0 / len).min(1.0);
        for k in 0..dim {
            xi[k] += scale * step[k];
        }
        if len < 1e-12 {
            return Some(xi);
        }
    }
    None
}
