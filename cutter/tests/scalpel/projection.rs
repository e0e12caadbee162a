//! Samples near the surface, not on it (a path file's points, the window's misses): the scalpel
//! cuts where they project onto the surface, so a path drawn a little outside or inside a
//! closed surface cuts one continuous groove along the same line as the path on it.

use super::*;

/// Crack tips of the cut so far: segment ends whose vertex was never copied (as the opening
/// finds them).
fn crack_tips(s: &Scalpel) -> usize {
    let m = s.dyn_mesh();
    let mut tips: Vec<u32> = s
        .segments()
        .iter()
        .flat_map(|seg| [seg.a, seg.b])
        .filter(|&v| m.copies(v).is_empty())
        .collect();
    tips.sort_unstable();
    tips.dedup();
    tips.len()
}

/// The wavy groove on a level-5 icosphere of radius 20 (edges about 0.8 long) with its samples
/// `offset` along the sphere's normal from the surface: how many crack tips it leaves, and the
/// largest distance of the cut from the path on the surface, in edge lengths.
fn groove_offset(offset: f64) -> (usize, f64) {
    let r = 20.0;
    let sphere = csg::testkit::icosphere(5, r);
    let h = (sphere.positions[sphere.triangles[0][0] as usize]
        - sphere.positions[sphere.triangles[0][1] as usize])
        .length();
    let on_surface = wavy_arc(r, 80);
    let drawn: Vec<DVec3> = on_surface.iter().map(|p| *p * ((r + offset) / r)).collect();
    let mut s = Scalpel::new(&sphere, ScalpelOptions::default().with_depth(0.75)).unwrap();
    groove_strokes(&mut s, &[drawn]);
    let (worst, n) = fidelity::worst_offset(&s, &on_surface, h);
    assert!(n > 40, "only {n} cut vertices measured");
    (crack_tips(&s), worst)
}

/// One edge length outside the sphere the cut used to count as stuck on a convex surface, end
/// and start again every few samples (a row of short grooves, each with its two tips). Now the
/// samples are projected: one groove, two tips, its vertices as close to the path as when the
/// path is drawn on the surface.
#[test]
fn a_path_off_the_surface_cuts_one_groove_along_it() {
    let (tips_on, worst_on) = groove_offset(0.0);
    println!("on the surface: {tips_on} tips, cut within {worst_on:.3} h of the path");
    assert_eq!(tips_on, 2);
    for offset in [0.8, 1.6, -0.8] {
        let (tips, worst) = groove_offset(offset);
        println!("{offset:+} off: {tips} tips, cut within {worst:.3} h of the path");
        assert_eq!(tips, 2, "a path {offset:+} off the surface cut {tips} tips");
        assert!(
            worst <= worst_on.max(0.25) + 0.05,
            "a path {offset:+} off the surface cut {worst:.3} h from it"
        );
    }
}
