//! A fallback font for the signs node and parameter docs use that egui's bundled Ubuntu lacks
//! (∇, →, ⁻, ⊙, combining marks, which it draws as boxes): the first installed system font that
//! has them all — DejaVu Sans on most Linux systems — found through fontdb and added after the
//! bundled fonts. None found: the signs stay boxes, and the log says so once.

use std::sync::Arc;

/// Signs of the docs (`hatchery nodes --markdown`) that Ubuntu Light has no glyph for.
const NEEDED: [char; 4] = ['∇', '→', '⁻', '⊙'];

/// Families tried first, in this order (wide coverage, common); then any installed face.
const PREFERRED: [&str; 4] = [
    "DejaVu Sans",
    "Noto Sans Math",
    "FreeSans",
    "Liberation Sans",
];

/// Adds the fallback to `ctx`'s fonts, if a system font has the signs.
pub fn install_math_fallback(ctx: &egui::Context) {
    let Some((data, index)) = math_font() else {
        tracing::info!("no installed font has ∇, →, ⊙: the docs show them as boxes");
        return;
    };
    let mut fonts = egui::FontDefinitions::default();
    let name = "system math fallback".to_owned();
    let font = egui::FontData {
        index,
        ..egui::FontData::from_owned(data)
    };
    fonts.font_data.insert(name.clone(), Arc::new(font));
    for family in [egui::FontFamily::Proportional, egui::FontFamily::Monospace] {
        fonts.families.entry(family).or_default().push(name.clone());
    }
    ctx.set_fonts(fonts);
}

/// The file and face index of the first regular system face that has every sign of [`NEEDED`].
fn math_font() -> Option<(Vec<u8>, u32)> {
    let mut db = fontdb::Database::new();
    db.load_system_fonts();
    let rank = |face: &fontdb::FaceInfo| {
        let family = face.families.first().map(|(name, _)| name.as_str());
        let preferred = PREFERRED
            .iter()
            .position(|p| Some(*p) == family)
            .unwrap_or(PREFERRED.len());
        let regular = face.style == fontdb::Style::Normal && face.weight == fontdb::Weight::NORMAL;
        (preferred, !regular)
    };
    let mut faces: Vec<&fontdb::FaceInfo> = db.faces().collect();
    faces.sort_by_key(|f| rank(f));
    faces.into_iter().find_map(|face| {
        db.with_face_data(face.id, |data, index| {
            let font = ab_glyph::FontRef::try_from_slice_and_index(data, index).ok()?;
            use ab_glyph::Font;
            NEEDED
                .iter()
                .all(|&c| font.glyph_id(c).0 != 0)
                .then(|| (data.to_vec(), index))
        })
        .flatten()
    })
}

#[cfg(test)]
mod tests {
    /// Where a system font has the signs (this machine: DejaVu Sans), it is found and has them.
    #[test]
    fn finds_a_system_font_with_the_signs_where_one_is_installed() {
        let dejavu = std::path::Path::new("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf");
        let Some((data, index)) = super::math_font() else {
            assert!(
                !dejavu.exists(),
                "DejaVu Sans is installed but was not found"
            );
            eprintln!("skipped: no installed font has the signs");
            return;
        };
        use ab_glyph::Font;
        let font = ab_glyph::FontRef::try_from_slice_and_index(&data, index).unwrap();
        assert!(super::NEEDED.iter().all(|&c| font.glyph_id(c).0 != 0));
    }
}
