//! The middle columns of `forces.csv` — `,joint,axis,group,` — which are the same in every
//! frame: formatted once per run rather than once per row.

use hagfish_sim::{DofLabel, GroupForces, RECORDED_GROUPS};

/// The `,joint,axis,group,` text of every row of a frame, in row order (group by group, DOF
/// by DOF), for the labels it was made from.
#[derive(Debug, Default)]
pub(crate) struct ForceColumns {
    labels: Vec<DofLabel>,
    text: Vec<String>,
}

impl ForceColumns {
    /// The columns of the rows of each recorded group for `labels` (one slice per group),
    /// formatted again only when the labels differ from the previous call's.
    pub(crate) fn for_labels(&mut self, labels: &[DofLabel]) -> std::slice::Chunks<'_, String> {
        if self.labels != labels {
            self.labels = labels.to_vec();
            self.text = RECORDED_GROUPS
                .iter()
                .flat_map(|&group| {
                    let name = GroupForces::group_name(group);
                    labels.iter().map(move |l| format!(",{},{},{name},", l.joint, l.axis))
                })
                .collect();
        }
        self.text.chunks(labels.len().max(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_slice_per_group_and_new_text_for_new_labels() {
        let mut columns = ForceColumns::default();
        let labels = [DofLabel { joint: 0, axis: 'X' }, DofLabel { joint: 3, axis: 'Z' }];
        let groups: Vec<&[String]> = columns.for_labels(&labels).collect();
        assert_eq!(groups.len(), RECORDED_GROUPS.len());
        let name = GroupForces::group_name(RECORDED_GROUPS[0]);
        assert_eq!(groups[0], [format!(",0,X,{name},"), format!(",3,Z,{name},")]);
        let other = [DofLabel { joint: 7, axis: 'Y' }];
        assert_eq!(
            columns.for_labels(&other).next().map(|g| g.to_vec()),
            Some(vec![format!(",7,Y,{name},")])
        );
    }
}
