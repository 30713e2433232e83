//! The R12 file's HEADER and TABLES sections, written by hand in the form the `dxf` crate
//! and the fix-up give them (the crate path, [`super::super::to_bytes_via_crate`], is the
//! reference: the tests compare whole files byte for byte on the command line's build,
//! which has the crate). The live page's module has no `dxf` crate (its code, with chrono,
//! uuid and image that it brings, was a tenth of the module), so the R12 file it offers is
//! this writer's and the entities' (`r12.rs`).
//!
//! Most of the head is fixed text. What depends on the drawing: the extents, the limits
//! (the sheet, [`super::super::sheet`]) and `$PINSBASE`, the dimension sizes (header and
//! DIMSTYLE), the DASHED pattern, a LAYER record per layer and the view (VPORT `*ACTIVE`).
//! The handles are the crate's: its fixed tables' records take 1 to F, the text style
//! [`crate::draw::dxf::TEXT_STYLE`] 10, the line type DASHED 11, the drawing's layers after the first (which
//! is written as layer `0`, handle 7) 12 on; the blocks and entities follow.

use super::{float, handle, hex, short, string};
use crate::draw::dxf::{LIMITS_MARGIN, layer_aci, linetype_name, sheet, snap};
use crate::draw::{Bounds, Drawing, parts};
use crate::geom::Point;

/// The handle of the second layer (the first is layer `0`, handle 7).
const SECOND_LAYER_HANDLE: u64 = 0x12;

/// The first handle after the tables: the first block's or entity's.
pub(super) fn first_handle(drawing: &Drawing) -> u64 {
    SECOND_LAYER_HANDLE + drawing.layers.len().saturating_sub(1) as u64
}

/// The numbers of the head that depend on the drawing (mm).
struct Values {
    ext_min: Point,
    ext_max: Point,
    lim_min: Point,
    lim_max: Point,
    text_height: f64,
    arrow_size: f64,
    ext_offset: f64,
    ext_extension: f64,
    text_gap: f64,
    dash: f64,
    gap: f64,
    center: Point,
    view_height: f64,
    aspect: f64,
}

impl Values {
    /// As the crate path sets them (`setup_header`, `setup_tables`).
    fn of(drawing: &Drawing) -> Values {
        let bounds = drawing.bounds().unwrap_or(Bounds { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) });
        let extent = bounds.width().max(bounds.height());
        let extent = if extent > 0.0 { extent } else { 1.0 };
        let (lim_min, lim_max) = sheet(drawing, &bounds, extent);
        let s = drawing.dim_style;
        let (dash, gap) = parts::dash_pattern(extent);
        let (w, h) = (bounds.width().max(1e-9 * extent), bounds.height().max(1e-9 * extent));
        Values {
            ext_min: bounds.min,
            ext_max: bounds.max,
            lim_min,
            lim_max,
            text_height: s.text_height,
            arrow_size: s.arrow_size,
            ext_offset: parts::EXT_LINE_GAP * s.arrow_size,
            ext_extension: parts::EXT_LINE_OVERSHOOT * s.arrow_size,
            text_gap: parts::LINEAR_TEXT_LIFT * s.text_height,
            dash,
            gap,
            center: Point::from((bounds.min.coords + bounds.max.coords) / 2.0),
            view_height: (1.0 + 2.0 * LIMITS_MARGIN) * h,
            aspect: w / h,
        }
    }
}

/// Appends the HEADER and TABLES sections of a validated drawing (in mm) to `o`, with
/// `$HANDSEED` = `handseed` (the handle after the file's last).
pub(super) fn write(o: &mut Vec<u8>, drawing: &Drawing, handseed: u64) {
    let v = Values::of(drawing);
    header(o, &v, handseed);
    tables(o, &v, drawing);
}

/// The HEADER section (R12's variables in the crate's order and defaults; `$DIMTXSTY` and
/// `$PINSBASE` as the fix-up adds them).
fn header(o: &mut Vec<u8>, v: &Values, handseed: u64) {
    o.extend_from_slice(
        concat!(
            "  0\r\nSECTION\r\n  2\r\nHEADER\r\n  9\r\n$ACADVER\r\n  1\r\nAC1009\r\n  9\r\n$INSBASE\r\n",
            " 10\r\n0.0\r\n 20\r\n0.0\r\n 30\r\n0.0\r\n  9\r\n$EXTMIN\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 10", snap(v.ext_min.x));
    float(o, b" 20", snap(v.ext_min.y));
    o.extend_from_slice(b" 30\r\n0.0\r\n  9\r\n$EXTMAX\r\n");
    float(o, b" 10", snap(v.ext_max.x));
    float(o, b" 20", snap(v.ext_max.y));
    o.extend_from_slice(b" 30\r\n0.0\r\n  9\r\n$LIMMIN\r\n");
    float(o, b" 10", snap(v.lim_min.x));
    float(o, b" 20", snap(v.lim_min.y));
    o.extend_from_slice(b"  9\r\n$LIMMAX\r\n");
    float(o, b" 10", snap(v.lim_max.x));
    float(o, b" 20", snap(v.lim_max.y));
    o.extend_from_slice(
        concat!(
            "  9\r\n$ORTHOMODE\r\n 70\r\n     0\r\n  9\r\n$REGENMODE\r\n 70\r\n     1\r\n  9\r\n$FILLMODE\r\n",
            " 70\r\n     1\r\n  9\r\n$QTEXTMODE\r\n 70\r\n     0\r\n  9\r\n$MIRRTEXT\r\n 70\r\n     0\r\n",
            "  9\r\n$DRAGMODE\r\n 70\r\n     2\r\n  9\r\n$LTSCALE\r\n 40\r\n1.0\r\n  9\r\n$OSMODE\r\n",
            " 70\r\n    37\r\n  9\r\n$ATTMODE\r\n 70\r\n     1\r\n  9\r\n$TEXTSIZE\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 40", v.text_height);
    o.extend_from_slice(
        concat!(
            "  9\r\n$TRACEWID\r\n 40\r\n0.05\r\n  9\r\n$TEXTSTYLE\r\n  7\r\nAZOMIX\r\n  9\r\n$DIMTXSTY\r\n",
            "  7\r\nAZOMIX\r\n  9\r\n$CLAYER\r\n  8\r\n0\r\n  9\r\n$CELTYPE\r\n  6\r\nBYLAYER\r\n",
            "  9\r\n$CECOLOR\r\n 62\r\n   256\r\n  9\r\n$DIMSCALE\r\n 40\r\n1.0\r\n  9\r\n$DIMASZ\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 40", v.arrow_size);
    o.extend_from_slice(b"  9\r\n$DIMEXO\r\n");
    float(o, b" 40", v.ext_offset);
    o.extend_from_slice(
        concat!(
            "  9\r\n$DIMDLI\r\n 40\r\n0.38\r\n  9\r\n$DIMRND\r\n 40\r\n0.0\r\n  9\r\n$DIMDLE\r\n",
            " 40\r\n0.0\r\n  9\r\n$DIMEXE\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 40", v.ext_extension);
    o.extend_from_slice(b"  9\r\n$DIMTP\r\n 40\r\n0.0\r\n  9\r\n$DIMTM\r\n 40\r\n0.0\r\n  9\r\n$DIMTXT\r\n");
    float(o, b" 40", v.text_height);
    o.extend_from_slice(
        concat!(
            "  9\r\n$DIMCEN\r\n 40\r\n0.09\r\n  9\r\n$DIMTSZ\r\n 40\r\n0.0\r\n  9\r\n$DIMTOL\r\n",
            " 70\r\n     0\r\n  9\r\n$DIMLIM\r\n 70\r\n     0\r\n  9\r\n$DIMTIH\r\n 70\r\n     0\r\n",
            "  9\r\n$DIMTOH\r\n 70\r\n     0\r\n  9\r\n$DIMSE1\r\n 70\r\n     0\r\n  9\r\n$DIMSE2\r\n",
            " 70\r\n     0\r\n  9\r\n$DIMTAD\r\n 70\r\n     1\r\n  9\r\n$DIMZIN\r\n 70\r\n     0\r\n",
            "  9\r\n$DIMBLK\r\n  1\r\n\r\n  9\r\n$DIMASO\r\n 70\r\n     1\r\n  9\r\n$DIMSHO\r\n",
            " 70\r\n     1\r\n  9\r\n$DIMPOST\r\n  1\r\n\r\n  9\r\n$DIMAPOST\r\n  1\r\n\r\n  9\r\n$DIMALT\r\n",
            " 70\r\n     0\r\n  9\r\n$DIMALTD\r\n 70\r\n     2\r\n  9\r\n$DIMALTF\r\n 40\r\n25.4\r\n",
            "  9\r\n$DIMLFAC\r\n 40\r\n1.0\r\n  9\r\n$DIMTOFL\r\n 70\r\n     0\r\n  9\r\n$DIMTVP\r\n",
            " 40\r\n0.0\r\n  9\r\n$DIMTIX\r\n 70\r\n     0\r\n  9\r\n$DIMSOXD\r\n 70\r\n     0\r\n",
            "  9\r\n$DIMSAH\r\n 70\r\n     0\r\n  9\r\n$DIMBLK1\r\n  1\r\n\r\n  9\r\n$DIMBLK2\r\n  1\r\n\r\n",
            "  9\r\n$DIMSTYLE\r\n  2\r\nSTANDARD\r\n  9\r\n$DIMCLRD\r\n 70\r\n     0\r\n  9\r\n$DIMCLRE\r\n",
            " 70\r\n     0\r\n  9\r\n$DIMCLRT\r\n 70\r\n     0\r\n  9\r\n$DIMTFAC\r\n 40\r\n1.0\r\n",
            "  9\r\n$DIMGAP\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 40", v.text_gap);
    o.extend_from_slice(
        concat!(
            "  9\r\n$LUNITS\r\n 70\r\n     2\r\n  9\r\n$LUPREC\r\n 70\r\n     4\r\n  9\r\n$SKETCHINC\r\n",
            " 40\r\n0.1\r\n  9\r\n$FILLETRAD\r\n 40\r\n0.0\r\n  9\r\n$AUNITS\r\n 70\r\n     0\r\n",
            "  9\r\n$AUPREC\r\n 70\r\n     0\r\n  9\r\n$MENU\r\n  1\r\n.\r\n  9\r\n$ELEVATION\r\n",
            " 40\r\n0.0\r\n  9\r\n$PELEVATION\r\n 40\r\n0.0\r\n  9\r\n$THICKNESS\r\n 40\r\n0.0\r\n",
            "  9\r\n$LIMCHECK\r\n 70\r\n     0\r\n  9\r\n$BLIPMODE\r\n 70\r\n     0\r\n  9\r\n$CHAMFERA\r\n",
            " 40\r\n0.0\r\n  9\r\n$CHAMFERB\r\n 40\r\n0.0\r\n  9\r\n$SKPOLY\r\n 70\r\n     0\r\n",
            "  9\r\n$TDCREATE\r\n 40\r\n2415021.0\r\n  9\r\n$TDUPDATE\r\n 40\r\n2415021.0\r\n",
            "  9\r\n$TDINDWG\r\n 40\r\n0.0\r\n  9\r\n$TDUSRTIMER\r\n 40\r\n0.0\r\n  9\r\n$USRTIMER\r\n",
            " 70\r\n     0\r\n  9\r\n$ANGBASE\r\n 50\r\n0.0\r\n  9\r\n$ANGDIR\r\n 70\r\n     0\r\n",
            "  9\r\n$PDMODE\r\n 70\r\n     0\r\n  9\r\n$PDSIZE\r\n 40\r\n0.0\r\n  9\r\n$PLINEWID\r\n",
            " 40\r\n0.0\r\n  9\r\n$COORDS\r\n 70\r\n     1\r\n  9\r\n$SPLFRAME\r\n 70\r\n     0\r\n",
            "  9\r\n$SPLINETYPE\r\n 70\r\n     6\r\n  9\r\n$SPLINESEGS\r\n 70\r\n     8\r\n  9\r\n$ATTDIA\r\n",
            " 70\r\n     1\r\n  9\r\n$ATTREQ\r\n 70\r\n     1\r\n  9\r\n$HANDLING\r\n 70\r\n     1\r\n",
            "  9\r\n$HANDSEED\r\n",
        )
        .as_bytes(),
    );
    o.extend_from_slice(b"  5\r\n");
    hex(o, handseed);
    o.extend_from_slice(b"\r\n");
    o.extend_from_slice(
        concat!(
            "  9\r\n$SURFTAB1\r\n 70\r\n     6\r\n  9\r\n$SURFTAB2\r\n 70\r\n     6\r\n  9\r\n$SURFTYPE\r\n",
            " 70\r\n     6\r\n  9\r\n$SURFU\r\n 70\r\n     6\r\n  9\r\n$SURFV\r\n 70\r\n     6\r\n",
            "  9\r\n$UCSNAME\r\n  2\r\n\r\n  9\r\n$UCSORG\r\n 10\r\n0.0\r\n 20\r\n0.0\r\n 30\r\n0.0\r\n",
            "  9\r\n$UCSXDIR\r\n 10\r\n1.0\r\n 20\r\n0.0\r\n 30\r\n0.0\r\n  9\r\n$UCSYDIR\r\n 10\r\n0.0\r\n",
            " 20\r\n1.0\r\n 30\r\n0.0\r\n  9\r\n$PUCSNAME\r\n  2\r\n\r\n  9\r\n$PUCSORG\r\n 10\r\n0.0\r\n",
            " 20\r\n0.0\r\n 30\r\n0.0\r\n  9\r\n$PUCSXDIR\r\n 10\r\n1.0\r\n 20\r\n0.0\r\n 30\r\n0.0\r\n",
            "  9\r\n$PUCSYDIR\r\n 10\r\n0.0\r\n 20\r\n1.0\r\n 30\r\n0.0\r\n  9\r\n$USERI1\r\n",
            " 70\r\n     0\r\n  9\r\n$USERI2\r\n 70\r\n     0\r\n  9\r\n$USERI3\r\n 70\r\n     0\r\n",
            "  9\r\n$USERI4\r\n 70\r\n     0\r\n  9\r\n$USERI5\r\n 70\r\n     0\r\n  9\r\n$USERR1\r\n",
            " 40\r\n0.0\r\n  9\r\n$USERR2\r\n 40\r\n0.0\r\n  9\r\n$USERR3\r\n 40\r\n0.0\r\n  9\r\n$USERR4\r\n",
            " 40\r\n0.0\r\n  9\r\n$USERR5\r\n 40\r\n0.0\r\n  9\r\n$WORLDVIEW\r\n 70\r\n     1\r\n",
            "  9\r\n$SHADEDGE\r\n 70\r\n     3\r\n  9\r\n$SHADEDIF\r\n 70\r\n    70\r\n  9\r\n$TILEMODE\r\n",
            " 70\r\n     1\r\n  9\r\n$MAXACTVP\r\n 70\r\n    64\r\n  9\r\n$PLIMCHECK\r\n 70\r\n     0\r\n",
            "  9\r\n$PEXTMIN\r\n 10\r\n100000000000000000000.0\r\n 20\r\n100000000000000000000.0\r\n",
            " 30\r\n100000000000000000000.0\r\n  9\r\n$PEXTMAX\r\n 10\r\n-100000000000000000000.0\r\n",
            " 20\r\n-100000000000000000000.0\r\n 30\r\n-100000000000000000000.0\r\n  9\r\n$PLIMMIN\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 10", snap(v.lim_min.x));
    float(o, b" 20", snap(v.lim_min.y));
    o.extend_from_slice(b"  9\r\n$PLIMMAX\r\n");
    float(o, b" 10", snap(v.lim_max.x));
    float(o, b" 20", snap(v.lim_max.y));
    o.extend_from_slice(b"  9\r\n$PINSBASE\r\n");
    float(o, b" 10", snap(-snap(v.lim_min.x)));
    float(o, b" 20", snap(-snap(v.lim_min.y)));
    o.extend_from_slice(
        concat!(
            " 30\r\n0.0\r\n  9\r\n$UNITMODE\r\n 70\r\n     0\r\n  9\r\n$VISRETAIN\r\n 70\r\n     1\r\n",
            "  9\r\n$PLINEGEN\r\n 70\r\n     0\r\n  9\r\n$PSLTSCALE\r\n 70\r\n     1\r\n  0\r\nENDSEC\r\n",
        )
        .as_bytes(),
    );
}

/// The TABLES section: APPID, DIMSTYLE, LTYPE, LAYER, STYLE (`TEXT_STYLE` = AZOMIX with
/// the font file arial.ttf, as in the text below), VPORT.
fn tables(o: &mut Vec<u8>, v: &Values, drawing: &Drawing) {
    o.extend_from_slice(
        concat!(
            "  0\r\nSECTION\r\n  2\r\nTABLES\r\n  0\r\nTABLE\r\n  2\r\nAPPID\r\n 70\r\n     0\r\n",
            "  0\r\nAPPID\r\n  5\r\n1\r\n  2\r\nACAD\r\n 70\r\n     0\r\n  0\r\nENDTAB\r\n  0\r\nTABLE\r\n",
            "  2\r\nDIMSTYLE\r\n 70\r\n     0\r\n  0\r\nDIMSTYLE\r\n105\r\n9\r\n  2\r\nSTANDARD\r\n",
            " 70\r\n     0\r\n  3\r\n\r\n  4\r\n\r\n  6\r\n\r\n  7\r\n\r\n 40\r\n1.0\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 41", v.arrow_size);
    float(o, b" 42", v.ext_offset);
    o.extend_from_slice(b" 43\r\n0.38\r\n");
    float(o, b" 44", v.ext_extension);
    o.extend_from_slice(
        concat!(
            " 45\r\n0.0\r\n 46\r\n0.0\r\n 47\r\n0.0\r\n 48\r\n0.0\r\n 71\r\n     0\r\n 72\r\n     0\r\n",
            " 73\r\n     0\r\n 74\r\n     0\r\n 75\r\n     0\r\n 76\r\n     0\r\n 77\r\n     1\r\n",
            " 78\r\n     0\r\n",
        )
        .as_bytes(),
    );
    float(o, b"140", v.text_height);
    o.extend_from_slice(b"141\r\n0.09\r\n142\r\n0.0\r\n143\r\n25.4\r\n144\r\n1.0\r\n145\r\n0.0\r\n146\r\n1.0\r\n");
    float(o, b"147", v.text_gap);
    o.extend_from_slice(
        concat!(
            "170\r\n     0\r\n171\r\n     2\r\n172\r\n     0\r\n173\r\n     0\r\n174\r\n     0\r\n",
            "175\r\n     0\r\n176\r\n     0\r\n177\r\n     0\r\n178\r\n     0\r\n  0\r\nENDTAB\r\n",
            "  0\r\nTABLE\r\n  2\r\nLTYPE\r\n 70\r\n     0\r\n  0\r\nLTYPE\r\n  5\r\nC\r\n  2\r\nBYBLOCK\r\n",
            " 70\r\n     0\r\n  3\r\n\r\n 72\r\n    65\r\n 73\r\n     0\r\n 40\r\n0.0\r\n  0\r\nLTYPE\r\n",
            "  5\r\nB\r\n  2\r\nBYLAYER\r\n 70\r\n     0\r\n  3\r\n\r\n 72\r\n    65\r\n 73\r\n     0\r\n",
            " 40\r\n0.0\r\n  0\r\nLTYPE\r\n  5\r\n8\r\n  2\r\nCONTINUOUS\r\n 70\r\n     0\r\n",
            "  3\r\nSolid line\r\n 72\r\n    65\r\n 73\r\n     0\r\n 40\r\n0.0\r\n  0\r\nLTYPE\r\n",
            "  5\r\n11\r\n  2\r\nDASHED\r\n 70\r\n     0\r\n  3\r\nDashed __ __ __\r\n 72\r\n    65\r\n",
            " 73\r\n     2\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 40", v.dash + v.gap);
    float(o, b" 49", v.dash);
    float(o, b" 49", -v.gap);
    o.extend_from_slice(b"  0\r\nENDTAB\r\n  0\r\nTABLE\r\n  2\r\nLAYER\r\n 70\r\n     0\r\n");
    layers(o, drawing);
    o.extend_from_slice(
        concat!(
            "  0\r\nENDTAB\r\n  0\r\nTABLE\r\n  2\r\nSTYLE\r\n 70\r\n     0\r\n  0\r\nSTYLE\r\n  5\r\nD\r\n",
            "  2\r\nSTANDARD\r\n 70\r\n     0\r\n 40\r\n0.0\r\n 41\r\n1.0\r\n 50\r\n0.0\r\n 71\r\n     0\r\n",
            " 42\r\n0.2\r\n  3\r\ntxt\r\n  4\r\n\r\n  0\r\nSTYLE\r\n  5\r\n10\r\n  2\r\nAZOMIX\r\n",
            " 70\r\n     0\r\n 40\r\n0.0\r\n 41\r\n1.0\r\n 50\r\n0.0\r\n 71\r\n     0\r\n 42\r\n0.2\r\n",
            "  3\r\narial.ttf\r\n  4\r\n\r\n  0\r\nENDTAB\r\n  0\r\nTABLE\r\n  2\r\nVPORT\r\n",
            " 70\r\n     0\r\n  0\r\nVPORT\r\n  5\r\nF\r\n  2\r\n*ACTIVE\r\n 70\r\n     0\r\n 10\r\n0.0\r\n",
            " 20\r\n0.0\r\n 11\r\n1.0\r\n 21\r\n1.0\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 12", snap(v.center.x));
    float(o, b" 22", snap(v.center.y));
    o.extend_from_slice(
        concat!(
            " 13\r\n0.0\r\n 23\r\n0.0\r\n 14\r\n1.0\r\n 24\r\n1.0\r\n 15\r\n1.0\r\n 25\r\n1.0\r\n",
            " 16\r\n0.0\r\n 26\r\n0.0\r\n 36\r\n1.0\r\n 17\r\n0.0\r\n 27\r\n0.0\r\n 37\r\n0.0\r\n",
        )
        .as_bytes(),
    );
    float(o, b" 40", v.view_height);
    float(o, b" 41", v.aspect);
    o.extend_from_slice(
        concat!(
            " 42\r\n50.0\r\n 43\r\n0.0\r\n 44\r\n0.0\r\n 50\r\n0.0\r\n 51\r\n0.0\r\n 71\r\n     0\r\n",
            " 72\r\n  1000\r\n 73\r\n     1\r\n 74\r\n     3\r\n 75\r\n     0\r\n 76\r\n     0\r\n",
            " 77\r\n     0\r\n 78\r\n     0\r\n  0\r\nENDTAB\r\n  0\r\nENDSEC\r\n",
        )
        .as_bytes(),
    );
}

/// The LAYER records: layer `0` with the drawing's first layer's colour, line type and state
/// (validation makes it the layer named `0`), then the other layers. A layer
/// that is off has a negative colour and is frozen (flag 1).
fn layers(o: &mut Vec<u8>, drawing: &Drawing) {
    for (i, layer) in drawing.layers.iter().enumerate() {
        let (h, name) = if i == 0 { (7, "0") } else { (SECOND_LAYER_HANDLE + i as u64 - 1, layer.name.as_str()) };
        let color = i16::from(layer_aci(layer.color));
        o.extend_from_slice(b"  0\r\nLAYER\r\n");
        handle(o, h);
        string(o, b"  2", name);
        short(o, b" 70", if layer.on { 0 } else { 1 });
        short(o, b" 62", if layer.on { color } else { -color });
        o.extend_from_slice(b"  6\r\n");
        o.extend_from_slice(linetype_name(layer.linetype).as_bytes());
        o.extend_from_slice(b"\r\n");
    }
}
