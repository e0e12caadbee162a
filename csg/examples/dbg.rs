#[path = "../tests/boolean_common/mod.rs"]
mod boolean_common;
use boolean_common::*;
use csg::{DVec3, TargetIndex};
fn main() {
    let target = snapped(&csg::testkit::torus(6.0, 2.0, 24, 12), 1.0 / 32.0);
    let g = 0.5;
    let (lo, size) = ((0, 3, -4), (11, 2, 1));
    let min = DVec3::new(lo.0 as f64, lo.1 as f64, lo.2 as f64) * g;
    let max = min + DVec3::new(size.0 as f64, size.1 as f64, size.2 as f64) * g;
    let cutter = csg::testkit::cube(min, max);
    let index = TargetIndex::build(target.clone()).unwrap();
    let r = csg::subtract(&index, &cutter).unwrap();
    println!("{:?}", r.stats);
    println!("{:?}", check_cut(&target, &r));
    let kept = r.materialize(&target);
    let kw = weld(&concat(&kept, &r.walls.mesh));
    let nk = kept.triangles.len();
    let _ = nk;
    // find edges used twice
    let mut m = std::collections::HashMap::new();
    for (f, t) in kw.triangles.iter().enumerate() { for k in 0..3 { m.entry((t[k], t[(k+1)%3])).or_insert(vec![]).push(f); } }
    for ((a,b), fs) in &m { if fs.len() != 1 || !m.contains_key(&(*b,*a)) {
        println!("edge {a}->{b} {:?} {:?} faces {:?} opp {:?}", kw.positions[*a as usize], kw.positions[*b as usize], fs, m.get(&(*b,*a)));
        for f in fs.iter().chain(m.get(&(*b,*a)).into_iter().flatten()) { let t = kw.triangles[*f]; println!("  f{f} {}: {:?}", if *f < nk {"kept"} else {"wall"}, t.map(|i| kw.positions[i as usize])); }
    }}
}
