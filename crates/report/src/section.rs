//! A section of `report.html` that another crate makes (the modes of the force field,
//! `hagfish_modes::report_section`): its heading, its HTML and its figures.

use std::fmt::Write as _;

use base64::Engine as _;
use base64::engine::general_purpose::STANDARD;

use crate::html::escape;
use crate::plots::Plot;

/// One extra section of the report, placed after the plots.
#[derive(Clone, Debug)]
pub struct Section {
    /// The `id` of its `<section>` element (letters, digits, `-`).
    pub id: String,
    /// Its heading (plain text; escaped).
    pub title: String,
    /// Its body: HTML the maker has escaped.
    pub html: String,
    /// Its figures, after the body, each captioned by its title (and its files, if in a
    /// folder).
    pub figures: Vec<Plot>,
    /// The folder of the run directory the figures' files are in (e.g. `modes/`), `None`
    /// for figures drawn for the report only.
    pub folder: Option<String>,
}

impl Section {
    /// The section as HTML.
    pub(crate) fn to_html(&self) -> String {
        let id: String =
            self.id.chars().filter(|c| c.is_ascii_alphanumeric() || *c == '-').collect();
        let mut out = format!("<section id=\"{id}\">\n<h2>{}</h2>\n", escape(&self.title));
        out.push_str(&self.html);
        for plot in &self.figures {
            out.push_str(&figure(plot, self.folder.as_deref()));
        }
        out.push_str("</section>\n");
        out
    }
}

/// A plot as an embedded PNG `<figure>` captioned by its title and, with a `folder`, its
/// files `{folder}{stem}.png` and `.svg`.
pub(crate) fn figure(plot: &Plot, folder: Option<&str>) -> String {
    let files = folder.map_or(String::new(), |f| {
        let (f, stem) = (escape(f), escape(&plot.stem));
        format!(" ({f}{stem}.png, {f}{stem}.svg)")
    });
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<figure><img class=\"check\" alt=\"{0}\" src=\"data:image/png;base64,{1}\">\
         <figcaption>{0}{files}</figcaption></figure>",
        escape(&plot.title),
        STANDARD.encode(&plot.png),
    );
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_section_escapes_its_title_and_id_and_embeds_its_figures() {
        let plot = Plot {
            stem: "s".into(),
            title: "a < b".into(),
            png: vec![1, 2, 3],
            svg: String::new(),
        };
        let section = Section {
            id: "modes\"><x".into(),
            title: "Modes & <waves>".into(),
            html: "<p>body</p>".into(),
            figures: vec![plot.clone()],
            folder: Some("modes/".into()),
        };
        let html = section.to_html();
        assert!(html.starts_with("<section id=\"modesx\">\n<h2>Modes &amp; &lt;waves&gt;</h2>"));
        assert!(html.contains("<p>body</p>"));
        assert!(html.contains("src=\"data:image/png;base64,AQID\""), "{html}");
        assert!(html.contains("a &lt; b (modes/s.png, modes/s.svg)"));
        assert!(html.ends_with("</section>\n"));
        let unfiled = Section { folder: None, figures: vec![plot], ..section };
        assert!(unfiled.to_html().contains("<figcaption>a &lt; b</figcaption>"));
    }
}
