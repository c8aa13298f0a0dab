//! Gauss quadrature in OOFEM's point order (spec §1.9): square rules loop ξ (outer) then η,
//! cube rules ξ, η, ζ (ζ innermost), wedge rules triangle point (outer) then line point.

use super::Shape;

/// A quadrature point: reference coordinates and weight.
#[derive(Debug, Clone, Copy)]
pub struct QuadPoint {
    pub xi: [f64; 3],
    pub weight: f64,
}

/// Gauss–Legendre points and weights on [−1, 1], ascending.
pub fn gauss_line(n: usize) -> Option<Vec<(f64, f64)>> {
    let r = match n {
        1 => vec![(0.0, 2.0)],
        2 => {
            let a = 1.0 / 3f64.sqrt();
            vec![(-a, 1.0), (a, 1.0)]
        }
        3 => {
            let a = (0.6f64).sqrt();
            vec![(-a, 5.0 / 9.0), (0.0, 8.0 / 9.0), (a, 5.0 / 9.0)]
        }
        4 => {
            let s = (6.0 / 5.0f64).sqrt() * 2.0;
            let a = ((3.0 - s) / 7.0).sqrt();
            let b = ((3.0 + s) / 7.0).sqrt();
            let wa = (18.0 + 30f64.sqrt()) / 36.0;
            let wb = (18.0 - 30f64.sqrt()) / 36.0;
            vec![(-b, wb), (-a, wa), (a, wa), (b, wb)]
        }
        5 => {
            let s = 2.0 * (10.0 / 7.0f64).sqrt();
            let a = (5.0 - s).sqrt() / 3.0;
            let b = (5.0 + s).sqrt() / 3.0;
            let wa = (322.0 + 13.0 * 70f64.sqrt()) / 900.0;
            let wb = (322.0 - 13.0 * 70f64.sqrt()) / 900.0;
            vec![(-b, wb), (-a, wa), (0.0, 128.0 / 225.0), (a, wa), (b, wb)]
        }
        _ => return None,
    };
    Some(r)
}

fn triangle(n: usize) -> Option<Vec<([f64; 2], f64)>> {
    match n {
        1 => Some(vec![([1.0 / 3.0, 1.0 / 3.0], 0.5)]),
        3 => {
            let (a, b) = (1.0 / 6.0, 2.0 / 3.0);
            Some(vec![
                ([a, a], 1.0 / 6.0),
                ([b, a], 1.0 / 6.0),
                ([a, b], 1.0 / 6.0),
            ])
        }
        4 => {
            let w1 = -27.0 / 96.0;
            let w2 = 25.0 / 96.0;
            Some(vec![
                ([1.0 / 3.0, 1.0 / 3.0], w1),
                ([0.2, 0.2], w2),
                ([0.6, 0.2], w2),
                ([0.2, 0.6], w2),
            ])
        }
        // Radon's rule, degree 5 (mass matrices of quadratic and axisymmetric triangles).
        7 => {
            let s15 = 15f64.sqrt();
            let mut out = vec![([1.0 / 3.0, 1.0 / 3.0], 9.0 / 80.0)];
            for (a, w) in [
                ((6.0 - s15) / 21.0, (155.0 - s15) / 2400.0),
                ((6.0 + s15) / 21.0, (155.0 + s15) / 2400.0),
            ] {
                let b = 1.0 - 2.0 * a;
                out.extend([([a, a], w), ([b, a], w), ([a, b], w)]);
            }
            Some(out)
        }
        _ => None,
    }
}

fn tetra(n: usize) -> Option<Vec<([f64; 3], f64)>> {
    match n {
        1 => Some(vec![([0.25, 0.25, 0.25], 1.0 / 6.0)]),
        4 => {
            let a = 0.585_410_196_624_968_5;
            let b = 0.138_196_601_125_010_5;
            let w = 1.0 / 24.0;
            Some(vec![
                ([a, b, b], w),
                ([b, a, b], w),
                ([b, b, a], w),
                ([b, b, b], w),
            ])
        }
        // Walkington's 14-point rule, degree 5 (mass matrices of quadratic tetrahedra).
        14 => {
            let mut out = Vec::with_capacity(14);
            for (a, w) in [
                (0.092_735_250_310_891_23, 0.012_248_840_519_393_66),
                (0.310_885_919_263_300_6, 0.018_781_320_953_002_64),
            ] {
                let b = 1.0 - 3.0 * a;
                out.extend([
                    ([a, a, a], w),
                    ([b, a, a], w),
                    ([a, b, a], w),
                    ([a, a, b], w),
                ]);
            }
            let (c, d, w) = (
                0.454_496_295_874_350_4,
                0.045_503_704_125_649_65,
                0.007_091_003_462_846_911,
            );
            out.extend([
                ([c, c, d], w),
                ([c, d, c], w),
                ([d, c, c], w),
                ([c, d, d], w),
                ([d, c, d], w),
                ([d, d, c], w),
            ]);
            Some(out)
        }
        _ => None,
    }
}

/// The integration rule with `nip` points for a shape, or None if OOFEM has no such rule here.
pub fn rule(shape: Shape, nip: usize) -> Option<Vec<QuadPoint>> {
    let mut out = Vec::new();
    match shape {
        Shape::Line2 | Shape::Line3 => {
            for (x, w) in gauss_line(nip)? {
                out.push(QuadPoint {
                    xi: [x, 0.0, 0.0],
                    weight: w,
                });
            }
        }
        Shape::Quad4 | Shape::Quad8 => {
            let n = (nip as f64).sqrt().round() as usize;
            if n * n != nip {
                return None;
            }
            let g = gauss_line(n)?;
            for &(x, wx) in &g {
                for &(y, wy) in &g {
                    out.push(QuadPoint {
                        xi: [x, y, 0.0],
                        weight: wx * wy,
                    });
                }
            }
        }
        Shape::Hexa8 | Shape::Hexa20 => {
            let n = (nip as f64).cbrt().round() as usize;
            if n * n * n != nip {
                return None;
            }
            let g = gauss_line(n)?;
            for &(x, wx) in &g {
                for &(y, wy) in &g {
                    for &(z, wz) in &g {
                        out.push(QuadPoint {
                            xi: [x, y, z],
                            weight: wx * wy * wz,
                        });
                    }
                }
            }
        }
        Shape::Tri3 | Shape::Tri6 => {
            for (p, w) in triangle(nip)? {
                out.push(QuadPoint {
                    xi: [p[0], p[1], 0.0],
                    weight: w,
                });
            }
        }
        Shape::Tet4 | Shape::Tet10 => {
            for (p, w) in tetra(nip)? {
                out.push(QuadPoint { xi: p, weight: w });
            }
        }
        Shape::Wedge6 => {
            let (ntri, nline) = match nip {
                2 => (1, 2),
                6 => (3, 2),
                9 => (3, 3),
                _ => return None,
            };
            for (p, wt) in triangle(ntri)? {
                for (z, wz) in gauss_line(nline)? {
                    out.push(QuadPoint {
                        xi: [p[0], p[1], z],
                        weight: wt * wz,
                    });
                }
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_line_integrates_polynomials_exactly() {
        for n in 1..=5 {
            let g = gauss_line(n).unwrap();
            for p in 0..2 * n {
                let num: f64 = g.iter().map(|(x, w)| w * x.powi(p as i32)).sum();
                let exact = if p % 2 == 1 {
                    0.0
                } else {
                    2.0 / (p as f64 + 1.0)
                };
                assert!((num - exact).abs() < 1e-13, "n={n} p={p}");
            }
        }
    }

    #[test]
    fn rules_have_reference_measure() {
        let cases = [
            (Shape::Quad4, 4, 4.0),
            (Shape::Quad8, 16, 4.0),
            (Shape::Hexa8, 8, 8.0),
            (Shape::Hexa8, 27, 8.0),
            (Shape::Tri3, 1, 0.5),
            (Shape::Tri3, 3, 0.5),
            (Shape::Tri3, 4, 0.5),
            (Shape::Tet4, 1, 1.0 / 6.0),
            (Shape::Tet4, 4, 1.0 / 6.0),
            (Shape::Wedge6, 6, 1.0),
        ];
        for (s, n, m) in cases {
            let r = rule(s, n).unwrap();
            assert_eq!(r.len(), n);
            assert!(
                (r.iter().map(|p| p.weight).sum::<f64>() - m).abs() < 1e-14,
                "{s:?} {n}"
            );
        }
    }

    #[test]
    fn triangle_and_tet_rules_integrate_quadratics() {
        // ∫_T x² = 1/12 on the unit triangle; ∫_tet x² = 1/60.
        for n in [3, 4] {
            let v: f64 = rule(Shape::Tri3, n)
                .unwrap()
                .iter()
                .map(|p| p.weight * p.xi[0] * p.xi[0])
                .sum();
            assert!((v - 1.0 / 12.0).abs() < 1e-14);
        }
        let v: f64 = rule(Shape::Tet4, 4)
            .unwrap()
            .iter()
            .map(|p| p.weight * p.xi[0] * p.xi[1])
            .sum();
        assert!((v - 1.0 / 120.0).abs() < 1e-14);
    }

    /// The mass rules (Radon's 7 points, Walkington's 14) integrate every monomial of degree ≤ 5
    /// exactly: ∫_T xⁱyʲ = i!j!/(i+j+2)!, ∫_tet xⁱyʲzᵏ = i!j!k!/(i+j+k+3)!.
    #[test]
    fn degree_five_rules_integrate_quintics() {
        let fact = |n: u32| (1..=n).map(f64::from).product::<f64>();
        for i in 0..=5u32 {
            for j in 0..=5 - i {
                let v: f64 = rule(Shape::Tri3, 7)
                    .unwrap()
                    .iter()
                    .map(|p| p.weight * p.xi[0].powi(i as i32) * p.xi[1].powi(j as i32))
                    .sum();
                let exact = fact(i) * fact(j) / fact(i + j + 2);
                assert!(
                    (v - exact).abs() < 1e-15,
                    "triangle x^{i} y^{j}: {v} vs {exact}"
                );
                for k in 0..=5 - i - j {
                    let v: f64 = rule(Shape::Tet4, 14)
                        .unwrap()
                        .iter()
                        .map(|p| {
                            p.weight
                                * p.xi[0].powi(i as i32)
                                * p.xi[1].powi(j as i32)
                                * p.xi[2].powi(k as i32)
                        })
                        .sum();
                    let exact = fact(i) * fact(j) * fact(k) / fact(i + j + k + 3);
                    assert!(
                        (v - exact).abs() < 1e-15,
                        "tetrahedron x^{i} y^{j} z^{k}: {v} vs {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn square_rule_order_is_xi_outer() {
        let r = rule(Shape::Quad4, 4).unwrap();
        let a = 1.0 / 3f64.sqrt();
        assert!((r[0].xi[0] + a).abs() < 1e-15 && (r[0].xi[1] + a).abs() < 1e-15);
        assert!((r[1].xi[0] + a).abs() < 1e-15 && (r[1].xi[1] - a).abs() < 1e-15);
    }
}
