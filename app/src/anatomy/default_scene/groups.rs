//! The model list's groups for the head atlas's labels, so that 300 structures read as a dozen
//! anatomical systems (ventricles, basal ganglia, brainstem, cortex, muscles …) instead of one
//! flat list. The atlas's label values follow a numbering scheme (1000s left cortex, 2000s right
//! cortex, 300s cerebellar lobules, 4000s head and neck muscles, 5000s sulci), but names are
//! more telling where the scheme mixes systems (the eyeballs sit among the muscles, the
//! ventricles among the deep nuclei), so a name's words decide first and the value range after.

/// The groups in the order the list shows them: the deep structures a cut reaches for first,
/// then the structures around them, outer last.
pub const ORDER: &[&str] = &[
    "ventricles",
    "basal ganglia",
    "limbic system",
    "thalamus and hypothalamus",
    "brainstem",
    "eyes and optic pathway",
    "cerebellum",
    "white matter",
    "cerebral cortex",
    "sulci",
    "muscles",
    "other",
];

/// Words of a label name (underscores as spaces) that put it in a group, first match wins.
const BY_WORDS: &[(&str, &[&str])] = &[
    (
        "ventricles",
        &["ventricle", "aqueduct", "choroid plexus", "pellucid septum"],
    ),
    (
        "eyes and optic pathway",
        &["eyeball", "optic", "rectus", "oblique", "levator palpebrae"],
    ),
    (
        "basal ganglia",
        &[
            "caudate",
            "putamen",
            "pallidus",
            "accumbens",
            "claustrum",
            "substantia nigra",
        ],
    ),
    (
        "limbic system",
        &[
            "hippocampus",
            "amygdala",
            "mammillary",
            "fornix",
            "mammillothalamic",
        ],
    ),
    (
        "thalamus and hypothalamus",
        &[
            "thalamus",
            "thalamic",
            "medullary lamina",
            "geniculate",
            "pulvinar",
            "hypothalamus",
            "pineal",
            "hypophysis",
            "infundibulum",
        ],
    ),
    (
        "brainstem",
        &[
            "pons",
            "midbrain",
            "medulla",
            "red nucleus",
            "colliculus",
            "peduncle",
        ],
    ),
    ("cerebellum", &["cerebell", "dentate", "fage"]),
    (
        "white matter",
        &["white matter", "corpus callosum", "commissure"],
    ),
    ("sulci", &["sulcus"]),
];

/// The group of a label, from its name (underscores or spaces) and value.
pub fn group_of(value: u32, name: &str) -> &'static str {
    let name = name.replace('_', " ").to_ascii_lowercase();
    // "oblique capitis" and "rectus capitis" are neck muscles, not eye muscles.
    let neck = name.contains("capitis");
    for &(group, words) in BY_WORDS {
        if words.iter().any(|w| name.contains(w)) && !(neck && group == "eyes and optic pathway") {
            return group;
        }
    }
    match value {
        300..=399 => "cerebellum",
        1000..=2999 => "cerebral cortex",
        4000..=4999 => "muscles",
        5000..=5999 => "sulci",
        _ => "other",
    }
}

/// Position of a group in [`ORDER`] (unknown groups last).
pub fn rank(group: &str) -> usize {
    ORDER
        .iter()
        .position(|g| *g == group)
        .unwrap_or(ORDER.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_decide_before_value_ranges() {
        assert_eq!(group_of(4, "left_lateral_ventricle"), "ventricles");
        assert_eq!(group_of(19, "aqueduct"), "ventricles");
        assert_eq!(group_of(4027, "left_eyeball"), "eyes and optic pathway");
        assert_eq!(
            group_of(4011, "left_medial_rectus"),
            "eyes and optic pathway"
        );
        assert_eq!(
            group_of(4071, "left_rectus_capitis_posterior_minor"),
            "muscles"
        );
        assert_eq!(group_of(4050, "tongue"), "muscles");
        assert_eq!(group_of(17, "left_hippocampus"), "limbic system");
        assert_eq!(group_of(12, "left_putamen"), "basal ganglia");
        assert_eq!(group_of(35, "pons"), "brainstem");
        assert_eq!(
            group_of(501, "left_internal_medullary_lamina"),
            "thalamus and hypothalamus"
        );
        assert_eq!(group_of(8, "left_cerebellar_cortex"), "cerebellum");
        assert_eq!(group_of(305, "left_VIIAf_v"), "cerebellum");
        assert_eq!(
            group_of(1028, "left_superior_frontal_gyrus"),
            "cerebral cortex"
        );
        assert_eq!(
            group_of(2, "white_matter_of_left_cerebral_hemisphere"),
            "white matter"
        );
        assert_eq!(group_of(5003, "left_central_sulcus"), "sulci");
        assert_eq!(group_of(9999, "mystery"), "other");
        for group in ORDER {
            assert_eq!(ORDER[rank(group)], *group);
        }
    }
}
