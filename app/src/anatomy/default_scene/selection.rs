//! Which of the atlas's labels the default scene shows. The atlas names over three hundred
//! structures; surfaced all together they weigh millions of triangles and most of them (cortex
//! gyri, white matter, cerebellar lobules, neck muscles) wrap around the deep structures a first
//! cut reaches for. The default is the skin plus the structures a user expects inside a head:
//! the ventricular system, the basal ganglia, the limbic structures, the thalamus (the atlas
//! splits it into its nuclei, which together make its shape), the brainstem, and the eyes with
//! the optic pathway: the structures of the atlas's own model files that earlier defaults
//! embedded, and the deep structures around them. Everything else stays one click away (File →
//! Open Example → the atlas with all structures, or File → Open of the atlas file).
//!
//! The list is of label values, so it does not depend on how a colour table spells a name.

/// The default scene's structures by anatomical system: what they are, and their label values.
pub const DEFAULT_SYSTEMS: &[(&str, &[u32])] = &[
    (
        "ventricles: lateral ventricles and their temporal horns, third and fourth, aqueduct",
        &[4, 43, 5, 44, 24, 15, 19],
    ),
    (
        "basal ganglia: caudate, putamen, globus pallidus externa and interna, accumbens, \
         substantia nigra",
        &[11, 50, 12, 51, 13, 52, 25, 83, 26, 58, 66, 71],
    ),
    ("limbic: hippocampus and amygdala", &[17, 53, 18, 54]),
    (
        "thalamus: its nuclei, right and left",
        &[
            500, 501, 502, 503, 504, 505, 506, 507, 508, 509, 510, 511, 512, 513, 514, 515, 516,
            517, 518, 519, 520, 521, 522, 523, 524, 525,
        ],
    ),
    (
        "brainstem: midbrain, pons, medulla oblongata",
        &[40, 35, 61],
    ),
    (
        "eyes and optic pathway: eyeballs, optic nerves, chiasm and tracts",
        &[4027, 4028, 77, 215, 85, 78, 216],
    ),
];

/// Every label value of the default scene's structures.
pub fn default_labels() -> impl Iterator<Item = u32> {
    DEFAULT_SYSTEMS
        .iter()
        .flat_map(|(_, values)| values.iter().copied())
}

/// True when the default scene shows the label `value`.
pub fn in_default(value: u32) -> bool {
    default_labels().any(|v| v == value)
}
