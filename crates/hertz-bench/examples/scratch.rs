use hertz_bench::mesh::Solid;
use hertz_bench::suite::Law;
use hertz_bench::verify::ConcentricCylinders;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kind = if a[1] == "tet" {
        Solid::Tet
    } else {
        Solid::Hex
    };
    let p = |i: usize| a[i].parse().unwrap();
    let text = ConcentricCylinders {
        kind,
        inner: p(2),
        outer: p(3),
        radial: p(4),
        layers: p(5),
        law: Law::Multiplier,
    }
    .input();
    std::fs::write(&a[6], text).unwrap();
}
