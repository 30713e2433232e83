//! The report's pages as one document to print: the live page's "report" download. The
//! page's module has no PDF writer, so it hands the browser the pages (each the report's SVG,
//! true size in paper mm) in an HTML document whose CSS page is the report's paper with no
//! margin: the browser's Print → Save as PDF (at 100 %, "fit to page" off) gives the
//! report's PDF, one sheet per page, every printed scale measuring true.

use crate::figure::shared::sheet::Paper;

/// The HTML document of `pages` (each an SVG of the report, `<svg …>` to `</svg>`, sized
/// in mm on `paper`), titled `title`: one printed sheet per page, landscape, no margin; on
/// screen the sheets one under the other with a line saying how to print them.
pub fn print_document(title: &str, paper: Paper, pages: &[&str]) -> String {
    let size = paper.size_mm();
    // Whole millimetres (297, 210, 420): `{}` writes them without a decimal point.
    let (w, h) = (size.x, size.y);
    let title = escape(title);
    let mut out = String::with_capacity(pages.iter().map(|p| p.len() + 40).sum::<usize>() + 1200);
    out.push_str(&format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{title}</title>\n<style>\n\
         @page {{ size: {w}mm {h}mm; margin: 0; }}\n\
         html, body {{ margin: 0; padding: 0; }}\n\
         .sheet {{ width: {w}mm; height: {h}mm; overflow: hidden; break-after: page; page-break-after: always; }}\n\
         .sheet:last-child {{ break-after: auto; page-break-after: auto; }}\n\
         .sheet svg {{ display: block; }}\n\
         @media screen {{ body {{ background: #777; }} .sheet {{ margin: 6mm auto; background: #fff; }}\n\
         .how {{ font: 14px sans-serif; color: #fff; text-align: center; margin: 4mm; }} }}\n\
         @media print {{ .how {{ display: none; }} }}\n\
         </style>\n</head>\n<body>\n\
         <p class=\"how\">{title}: {n} pages on {paper} landscape. Print at 100 % (no scaling, no margins; \
         Print → Save as PDF gives the report's PDF) so that every printed scale measures true.</p>\n",
        n = pages.len(),
        paper = paper.name(),
    ));
    for p in pages {
        out.push_str("<div class=\"sheet\">\n");
        out.push_str(p.trim());
        out.push_str("\n</div>\n");
    }
    out.push_str("</body>\n</html>\n");
    out
}

/// `s` with the characters HTML gives a meaning to written as entities.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}
