//! The model list's tree: models grouped by `model.group` (folder names, `/` between them),
//! filtered by the text in the list's filter box. Pure data, so the grouping and the filter are
//! tested without a window.

use crate::scene::SceneModel;

/// One group of the list (the root has an empty name and path).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GroupNode {
    /// The last folder name (`sub` of `atlas/sub`).
    pub name: String,
    /// The whole group path (`atlas/sub`); unique, so it identifies the node's UI state.
    pub path: String,
    /// Sub-groups in the order their first model appears in the scene.
    pub groups: Vec<GroupNode>,
    /// Indices into the scene's models directly in this group, in scene order.
    pub models: Vec<usize>,
}

impl GroupNode {
    /// The tree of the models that pass `filter` ([`matches`]); groups left without a model are
    /// not in it.
    pub fn build(models: &[SceneModel], filter: &str) -> GroupNode {
        let mut root = GroupNode::default();
        for (index, model) in models.iter().enumerate() {
            if !matches(model, filter) {
                continue;
            }
            let mut node = &mut root;
            for name in model.model.group.split('/').filter(|n| !n.is_empty()) {
                let path = if node.path.is_empty() {
                    name.to_string()
                } else {
                    format!("{}/{name}", node.path)
                };
                let slot = match node.groups.iter().position(|g| g.name == name) {
                    Some(slot) => slot,
                    None => {
                        node.groups.push(GroupNode {
                            name: name.to_string(),
                            path,
                            ..GroupNode::default()
                        });
                        node.groups.len() - 1
                    }
                };
                node = &mut node.groups[slot];
            }
            node.models.push(index);
        }
        root
    }

    /// Every model in this group and its sub-groups.
    pub fn all_models(&self) -> Vec<usize> {
        let mut out = self.models.clone();
        for group in &self.groups {
            out.extend(group.all_models());
        }
        out
    }

    /// True when `index` is in this group or one of its sub-groups.
    pub fn contains(&self, index: usize) -> bool {
        self.models.contains(&index) || self.groups.iter().any(|g| g.contains(index))
    }
}

/// True when every word of `filter` occurs (ignoring case) in the model's name or group; an
/// empty filter passes everything.
pub fn matches(model: &SceneModel, filter: &str) -> bool {
    let name = model.model.name.to_lowercase();
    let group = model.model.group.to_lowercase();
    filter
        .split_whitespace()
        .map(str::to_lowercase)
        .all(|word| name.contains(&word) || group.contains(&word))
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;

    fn model(name: &str, group: &str) -> SceneModel {
        let mut m = SceneModel::new(name, "x.obj", Arc::new(csg::Mesh::default()), [1.0; 3]);
        m.model.group = group.to_string();
        m
    }

    #[test]
    fn groups_nest_by_folder_and_keep_scene_order() {
        let models = [
            model("skin", ""),
            model("left hippocampus", "atlas"),
            model("pons", "atlas/brainstem"),
            model("right hippocampus", "atlas"),
            model("medulla", "atlas/brainstem"),
        ];
        let root = GroupNode::build(&models, "");
        assert_eq!(root.models, [0]);
        assert_eq!(root.groups.len(), 1);
        let atlas = &root.groups[0];
        assert_eq!(
            (atlas.name.as_str(), atlas.path.as_str()),
            ("atlas", "atlas")
        );
        assert_eq!(atlas.models, [1, 3]);
        assert_eq!(atlas.groups[0].path, "atlas/brainstem");
        assert_eq!(atlas.groups[0].models, [2, 4]);
        assert_eq!(atlas.all_models(), [1, 3, 2, 4]);
        assert!(atlas.contains(4) && !atlas.contains(0));
    }

    #[test]
    fn the_filter_matches_every_word_in_name_or_group_ignoring_case() {
        let models = [
            model("left hippocampus", "atlas"),
            model("right hippocampus", "atlas"),
            model("pons", "atlas/brainstem"),
            model("skin", ""),
        ];
        let root = GroupNode::build(&models, "HIPPO left");
        assert_eq!(root.all_models(), [0]);
        let root = GroupNode::build(&models, "brainstem");
        assert_eq!(root.all_models(), [2]);
        assert!(root.models.is_empty(), "skin is filtered out");
        let root = GroupNode::build(&models, "nothing like it");
        assert_eq!(root, GroupNode::default(), "empty groups are dropped");
    }
}
