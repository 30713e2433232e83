let wasm_bindgen = (function(exports) {
    let script_src;
    if (typeof document !== 'undefined' && document.currentScript !== null) {
        script_src = new URL(document.currentScript.src, location.href).toString();
    }

    /**
     * A run's files, handed to JavaScript one by one.
     */
    class Files {
        static __wrap(ptr) {
            const obj = Object.create(Files.prototype);
            obj.__wbg_ptr = ptr;
            FilesFinalization.register(obj, obj.__wbg_ptr, obj);
            return obj;
        }
        __destroy_into_raw() {
            const ptr = this.__wbg_ptr;
            this.__wbg_ptr = 0;
            FilesFinalization.unregister(this);
            return ptr;
        }
        free() {
            const ptr = this.__destroy_into_raw();
            wasm.__wbg_files_free(ptr, 0);
        }
        /**
         * File `i`'s bytes (a `Uint8Array`; empty past the end).
         * @param {number} i
         * @returns {Uint8Array}
         */
        bytes(i) {
            const ret = wasm.files_bytes(this.__wbg_ptr, i);
            var v1 = getArrayU8FromWasm0(ret[0], ret[1]).slice();
            wasm.__wbindgen_free(ret[0], ret[1] * 1, 1);
            return v1;
        }
        /**
         * How many files.
         * @returns {number}
         */
        count() {
            const ret = wasm.files_count(this.__wbg_ptr);
            return ret >>> 0;
        }
        /**
         * File `i`'s path relative to the output directory (`""` past the end).
         * @param {number} i
         * @returns {string}
         */
        name(i) {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.files_name(this.__wbg_ptr, i);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The report the command line prints on stderr.
         * @returns {string}
         */
        report() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.files_report(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The JSON summary, pretty (as `--json` prints it).
         * @returns {string}
         */
        summary() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.files_summary(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The warnings, one a line.
         * @returns {string}
         */
        warnings() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.files_warnings(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
    }
    if (Symbol.dispose) Files.prototype[Symbol.dispose] = Files.prototype.free;
    exports.Files = Files;

    /**
     * A scene open in the page ([`Session`](super::Session)): every method that changes it
     * throws the command line's message and leaves it as it was on an error.
     */
    class Live {
        __destroy_into_raw() {
            const ptr = this.__wbg_ptr;
            this.__wbg_ptr = 0;
            LiveFinalization.unregister(this);
            return ptr;
        }
        free() {
            const ptr = this.__destroy_into_raw();
            wasm.__wbg_live_free(ptr, 0);
        }
        /**
         * A motion's base SVG, shared by every frame (`""` for a still picture).
         * @returns {string}
         */
        base() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_base(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * A synthesis's designed scene (`<name>-design.toml`), to open in the page; `""` for the
         * other kinds.
         * @returns {string}
         */
        design() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_design(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The file name of a synthesis's designed scene (`<name>-design.toml`: the page's title
         * and storage key once the design is opened); `""` for the other kinds.
         * @returns {string}
         */
        design_file() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_design_file(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * Each diagram's marker at position `k` as JSON `[[x, y] or null, ...]`, SVG user units.
         * @param {number} k
         * @returns {string}
         */
        diagram_markers(k) {
            let deferred2_0;
            let deferred2_1;
            try {
                const ret = wasm.live_diagram_markers(this.__wbg_ptr, k);
                var ptr1 = ret[0];
                var len1 = ret[1];
                if (ret[3]) {
                    ptr1 = 0; len1 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred2_0 = ptr1;
                deferred2_1 = len1;
                return getStringFromWasm0(ptr1, len1);
            } finally {
                wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
            }
        }
        /**
         * The scene's diagrams as JSON: `[[stem, svg], ...]` (made when first asked for
         * after a change).
         * @returns {string}
         */
        diagrams() {
            let deferred2_0;
            let deferred2_1;
            try {
                const ret = wasm.live_diagrams(this.__wbg_ptr);
                var ptr1 = ret[0];
                var len1 = ret[1];
                if (ret[3]) {
                    ptr1 = 0; len1 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred2_0 = ptr1;
                deferred2_1 = len1;
                return getStringFromWasm0(ptr1, len1);
            } finally {
                wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
            }
        }
        /**
         * Drags `point` towards the model point (`x`, `y`); returns the state reached as
         * [`Live::points`] gives it, with `"drive"` (φ1 in degrees, or t in seconds) and
         * `"position"` (the nearest position).
         * @param {string} point
         * @param {number} x
         * @param {number} y
         * @returns {string}
         */
        drag(point, x, y) {
            let deferred5_0;
            let deferred5_1;
            try {
                const val2 = +x;
                const val3 = +y;
                const ptr0 = passStringToWasm0(point, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                const len0 = WASM_VECTOR_LEN;
                const ret = wasm.live_drag(this.__wbg_ptr, ptr0, len0, val2, val3);
                var ptr4 = ret[0];
                var len4 = ret[1];
                if (ret[3]) {
                    ptr4 = 0; len4 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred5_0 = ptr4;
                deferred5_1 = len4;
                return getStringFromWasm0(ptr4, len4);
            } finally {
                wasm.__wbindgen_free(deferred5_0, deferred5_1, 1);
            }
        }
        /**
         * The frame where the last drag left the mechanism (`""` before any drag).
         * @returns {string}
         */
        dragged_frame() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_dragged_frame(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * What the dragged frame draws on the base (`""`: draw [`Live::dragged_frame`]).
         * @returns {string}
         */
        dragged_moving() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_dragged_moving(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The points edit mode drags at position `k`, as JSON `[[name, x, y], ...]` (`""`
         * for a still picture).
         * @param {number} k
         * @returns {string}
         */
        edit_points(k) {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_edit_points(this.__wbg_ptr, k);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The scene's file name, as messages give it.
         * @returns {string}
         */
        file() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_file(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * The files of the scene as it stands (without frames), for downloads.
         * @returns {Files}
         */
        files() {
            const ret = wasm.live_files(this.__wbg_ptr);
            if (ret[2]) {
                throw takeFromExternrefTable0(ret[1]);
            }
            return Files.__wrap(ret[0]);
        }
        /**
         * Position `k`'s frame, an SVG document (`""` past the last).
         * @param {number} k
         * @returns {string}
         */
        frame(k) {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_frame(this.__wbg_ptr, k);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * Position `k`'s label.
         * @param {number} k
         * @returns {string}
         */
        label(k) {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_label(this.__wbg_ptr, k);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * A triad's modes as JSON (`{"phi1_deg": [...], "pattern_phi1_deg", "drawn"}`), `""`
         * for the other kinds.
         * @returns {string}
         */
        modes() {
            let deferred2_0;
            let deferred2_1;
            try {
                const ret = wasm.live_modes(this.__wbg_ptr);
                var ptr1 = ret[0];
                var len1 = ret[1];
                if (ret[3]) {
                    ptr1 = 0; len1 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred2_0 = ptr1;
                deferred2_1 = len1;
                return getStringFromWasm0(ptr1, len1);
            } finally {
                wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
            }
        }
        /**
         * What position `k`'s frame draws on the base (`""`: draw [`Live::frame`] whole).
         * @param {number} k
         * @returns {string}
         */
        moving(k) {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_moving(this.__wbg_ptr, k);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * Opens the scene in `toml`, named `file` in messages.
         * @param {string} toml
         * @param {string} file
         */
        constructor(toml, file) {
            let ptr0, len0, ptr1, len1;
            try {
                ptr0 = passStringToWasm0(toml, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len0 = WASM_VECTOR_LEN;
                ptr1 = passStringToWasm0(file, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len1 = WASM_VECTOR_LEN;
            } catch (e) {
                if (ptr1) { wasm.__wbindgen_free(ptr1, len1 * 1, 1); }
                if (ptr0) { wasm.__wbindgen_free(ptr0, len0 * 1, 1); }
                throw e;
            }
            const ret = wasm.live_new(ptr0, len0, ptr1, len1);
            if (ret[2]) {
                throw takeFromExternrefTable0(ret[1]);
            }
            this.__wbg_ptr = ret[0];
            LiveFinalization.register(this, this.__wbg_ptr, this);
            return this;
        }
        /**
         * Every number of the scene as JSON: `[{"path", "value", "integer", "label", "unit",
         * "group", "min", "max", "detail"}, ...]`.
         * @returns {string}
         */
        parameters() {
            let deferred2_0;
            let deferred2_1;
            try {
                const ret = wasm.live_parameters(this.__wbg_ptr);
                var ptr1 = ret[0];
                var len1 = ret[1];
                if (ret[3]) {
                    ptr1 = 0; len1 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred2_0 = ptr1;
                deferred2_1 = len1;
                return getStringFromWasm0(ptr1, len1);
            } finally {
                wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
            }
        }
        /**
         * Position `k`'s named points as JSON (`{"label", "points": [[name, x, y], ...],
         * "residual"}`, model units; `""` for a still picture).
         * @param {number} k
         * @returns {string}
         */
        points(k) {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_points(this.__wbg_ptr, k);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * Number of positions (1 for a still picture).
         * @returns {number}
         */
        positions() {
            const ret = wasm.live_positions(this.__wbg_ptr);
            return ret >>> 0;
        }
        /**
         * The scene's file name in messages from now on (`file`, a design's `<name>-design.toml`).
         * @param {string} file
         */
        rename(file) {
            const ptr0 = passStringToWasm0(file, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            const len0 = WASM_VECTOR_LEN;
            wasm.live_rename(this.__wbg_ptr, ptr0, len0);
        }
        /**
         * A new scene text (the TOML editor, an undo, a build step), and solve again.
         * @param {string} toml
         */
        replace(toml) {
            const ptr0 = passStringToWasm0(toml, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            const len0 = WASM_VECTOR_LEN;
            const ret = wasm.live_replace(this.__wbg_ptr, ptr0, len0);
            if (ret[1]) {
                throw takeFromExternrefTable0(ret[0]);
            }
        }
        /**
         * The report of the scene as it stands (`paper` `a4` or `a3`, `positions` as
         * `--positions` takes it, `""` for the report's choice), as the page offers it: its
         * pages in one HTML document to print to PDF, its table and JSON (the PDF is the command
         * line's: this module has no PDF writer).
         * @param {string} paper
         * @param {string} positions
         * @returns {Files}
         */
        report(paper, positions) {
            let ptr0, len0, ptr1, len1;
            try {
                ptr0 = passStringToWasm0(paper, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len0 = WASM_VECTOR_LEN;
                ptr1 = passStringToWasm0(positions, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len1 = WASM_VECTOR_LEN;
            } catch (e) {
                if (ptr1) { wasm.__wbindgen_free(ptr1, len1 * 1, 1); }
                if (ptr0) { wasm.__wbindgen_free(ptr0, len0 * 1, 1); }
                throw e;
            }
            const ret = wasm.live_report(this.__wbg_ptr, ptr0, len0, ptr1, len1);
            if (ret[2]) {
                throw takeFromExternrefTable0(ret[1]);
            }
            return Files.__wrap(ret[0]);
        }
        /**
         * Edit mode: `point` dragged to (`x`, `y`) at position `k` changes the dimensions it
         * carries (written with `decimals` decimals); the scene is solved again.
         * @param {string} point
         * @param {number} x
         * @param {number} y
         * @param {number} k
         * @param {number} decimals
         */
        reshape(point, x, y, k, decimals) {
            const val2 = +x;
            const val3 = +y;
            const val4 = +k;
            const val5 = +decimals;
            const ptr0 = passStringToWasm0(point, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            const len0 = WASM_VECTOR_LEN;
            const ret = wasm.live_reshape(this.__wbg_ptr, ptr0, len0, val2, val3, val4, val5);
            if (ret[1]) {
                throw takeFromExternrefTable0(ret[0]);
            }
        }
        /**
         * The scene's text as it stands.
         * @returns {string}
         */
        scene_text() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_scene_text(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
        /**
         * `--set path=value` written into the text, and solve again.
         * @param {string} path
         * @param {string} value
         */
        set(path, value) {
            let ptr0, len0, ptr1, len1;
            try {
                ptr0 = passStringToWasm0(path, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len0 = WASM_VECTOR_LEN;
                ptr1 = passStringToWasm0(value, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len1 = WASM_VECTOR_LEN;
            } catch (e) {
                if (ptr1) { wasm.__wbindgen_free(ptr1, len1 * 1, 1); }
                if (ptr0) { wasm.__wbindgen_free(ptr0, len0 * 1, 1); }
                throw e;
            }
            const ret = wasm.live_set(this.__wbg_ptr, ptr0, len0, ptr1, len1);
            if (ret[1]) {
                throw takeFromExternrefTable0(ret[0]);
            }
        }
        /**
         * The scene's sheets as JSON: `[[suffix, svg], ...]` (made when first asked for
         * after a change).
         * @returns {string}
         */
        sheets() {
            let deferred2_0;
            let deferred2_1;
            try {
                const ret = wasm.live_sheets(this.__wbg_ptr);
                var ptr1 = ret[0];
                var len1 = ret[1];
                if (ret[3]) {
                    ptr1 = 0; len1 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred2_0 = ptr1;
                deferred2_1 = len1;
                return getStringFromWasm0(ptr1, len1);
            } finally {
                wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
            }
        }
        /**
         * The JSON summary, pretty (made when first asked for after a change).
         * @returns {string}
         */
        summary() {
            let deferred2_0;
            let deferred2_1;
            try {
                const ret = wasm.live_summary(this.__wbg_ptr);
                var ptr1 = ret[0];
                var len1 = ret[1];
                if (ret[3]) {
                    ptr1 = 0; len1 = 0;
                    throw takeFromExternrefTable0(ret[2]);
                }
                deferred2_0 = ptr1;
                deferred2_1 = len1;
                return getStringFromWasm0(ptr1, len1);
            } finally {
                wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
            }
        }
        /**
         * SVG user units per model unit of the frames.
         * @returns {number}
         */
        user_units_per_model() {
            const ret = wasm.live_user_units_per_model(this.__wbg_ptr);
            return ret;
        }
        /**
         * The warnings, one a line.
         * @returns {string}
         */
        warnings() {
            let deferred1_0;
            let deferred1_1;
            try {
                const ret = wasm.live_warnings(this.__wbg_ptr);
                deferred1_0 = ret[0];
                deferred1_1 = ret[1];
                return getStringFromWasm0(ret[0], ret[1]);
            } finally {
                wasm.__wbindgen_free(deferred1_0, deferred1_1, 1);
            }
        }
    }
    if (Symbol.dispose) Live.prototype[Symbol.dispose] = Live.prototype.free;
    exports.Live = Live;

    /**
     * `toml` after a build step (JSON, [`build::Step`]: `{"tool": "link", "ends": ["ground.O1",
     * [0.04, 0.0]]}`), coordinates written with `decimals` decimals.
     * @param {string} toml
     * @param {string} file
     * @param {string} step
     * @param {number} decimals
     * @returns {string}
     */
    function build_step(toml, file, step, decimals) {
        let deferred6_0;
        let deferred6_1;
        try {
            const val4 = +decimals;
            let ptr0, len0, ptr1, len1, ptr2, len2;
            try {
                ptr0 = passStringToWasm0(toml, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len0 = WASM_VECTOR_LEN;
                ptr1 = passStringToWasm0(file, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len1 = WASM_VECTOR_LEN;
                ptr2 = passStringToWasm0(step, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
                len2 = WASM_VECTOR_LEN;
            } catch (e) {
                if (ptr2) { wasm.__wbindgen_free(ptr2, len2 * 1, 1); }
                if (ptr1) { wasm.__wbindgen_free(ptr1, len1 * 1, 1); }
                if (ptr0) { wasm.__wbindgen_free(ptr0, len0 * 1, 1); }
                throw e;
            }
            const ret = wasm.build_step(ptr0, len0, ptr1, len1, ptr2, len2, val4);
            var ptr5 = ret[0];
            var len5 = ret[1];
            if (ret[3]) {
                ptr5 = 0; len5 = 0;
                throw takeFromExternrefTable0(ret[2]);
            }
            deferred6_0 = ptr5;
            deferred6_1 = len5;
            return getStringFromWasm0(ptr5, len5);
        } finally {
            wasm.__wbindgen_free(deferred6_0, deferred6_1, 1);
        }
    }
    exports.build_step = build_step;

    /**
     * The scene's text in a share link's fragment value; throws what is wrong with the link.
     * @param {string} link
     * @returns {string}
     */
    function open_share_link(link) {
        let deferred3_0;
        let deferred3_1;
        try {
            const ptr0 = passStringToWasm0(link, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            const len0 = WASM_VECTOR_LEN;
            const ret = wasm.open_share_link(ptr0, len0);
            var ptr2 = ret[0];
            var len2 = ret[1];
            if (ret[3]) {
                ptr2 = 0; len2 = 0;
                throw takeFromExternrefTable0(ret[2]);
            }
            deferred3_0 = ptr2;
            deferred3_1 = len2;
            return getStringFromWasm0(ptr2, len2);
        } finally {
            wasm.__wbindgen_free(deferred3_0, deferred3_1, 1);
        }
    }
    exports.open_share_link = open_share_link;

    /**
     * Solves the scene in `toml` (named `file` in messages) and returns its files, with a
     * motion's frames and viewer when `frames`; throws the command line's error message.
     * @param {string} toml
     * @param {string} file
     * @param {boolean} frames
     * @returns {Files}
     */
    function run_scene(toml, file, frames) {
        const val3 = +frames;
        let ptr0, len0, ptr1, len1;
        try {
            ptr0 = passStringToWasm0(toml, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            len0 = WASM_VECTOR_LEN;
            ptr1 = passStringToWasm0(file, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            len1 = WASM_VECTOR_LEN;
        } catch (e) {
            if (ptr1) { wasm.__wbindgen_free(ptr1, len1 * 1, 1); }
            if (ptr0) { wasm.__wbindgen_free(ptr0, len0 * 1, 1); }
            throw e;
        }
        const ret = wasm.run_scene(ptr0, len0, ptr1, len1, val3);
        if (ret[2]) {
            throw takeFromExternrefTable0(ret[1]);
        }
        return Files.__wrap(ret[0]);
    }
    exports.run_scene = run_scene;

    /**
     * The share link's fragment value for `toml` (`v1.…`).
     * @param {string} toml
     * @returns {string}
     */
    function share_link(toml) {
        let deferred2_0;
        let deferred2_1;
        try {
            const ptr0 = passStringToWasm0(toml, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            const len0 = WASM_VECTOR_LEN;
            const ret = wasm.share_link(ptr0, len0);
            deferred2_0 = ret[0];
            deferred2_1 = ret[1];
            return getStringFromWasm0(ret[0], ret[1]);
        } finally {
            wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
        }
    }
    exports.share_link = share_link;

    /**
     * The sketch of `toml` as JSON ([`build::Sketch`]); `""` when the text is not TOML.
     * @param {string} toml
     * @returns {string}
     */
    function sketch(toml) {
        let deferred2_0;
        let deferred2_1;
        try {
            const ptr0 = passStringToWasm0(toml, wasm.__wbindgen_malloc, wasm.__wbindgen_realloc);
            const len0 = WASM_VECTOR_LEN;
            const ret = wasm.sketch(ptr0, len0);
            deferred2_0 = ret[0];
            deferred2_1 = ret[1];
            return getStringFromWasm0(ret[0], ret[1]);
        } finally {
            wasm.__wbindgen_free(deferred2_0, deferred2_1, 1);
        }
    }
    exports.sketch = sketch;
    function __wbg_get_imports() {
        const import0 = {
            __proto__: null,
            __wbg___wbindgen_throw_4c88d8bf264fd984: function(arg0, arg1) {
                throw new Error(getStringFromWasm0(arg0, arg1));
            },
            __wbindgen_generic_0000000000000001: function(arg0, arg1) {
                // Cast intrinsic for `Ref(String) -> Externref`.
                const ret = getStringFromWasm0(arg0, arg1);
                return ret;
            },
            __wbindgen_init_externref_table: function() {
                const table = wasm.__wbindgen_externrefs;
                table.set(0, undefined);
                table.set(1024, undefined);
                table.set(1025, null);
                table.set(1026, true);
                table.set(1027, false);
            },
        };
        return {
            __proto__: null,
            "./mechdraw_bg.js": import0,
        };
    }

    const FilesFinalization = (typeof FinalizationRegistry === 'undefined')
        ? { register: () => {}, unregister: () => {} }
        : new FinalizationRegistry(ptr => wasm.__wbg_files_free(ptr, 1));
    const LiveFinalization = (typeof FinalizationRegistry === 'undefined')
        ? { register: () => {}, unregister: () => {} }
        : new FinalizationRegistry(ptr => wasm.__wbg_live_free(ptr, 1));

    function getArrayU8FromWasm0(ptr, len) {
        ptr = ptr >>> 0;
        return getUint8ArrayMemory0().subarray(ptr / 1, ptr / 1 + len);
    }

    function getStringFromWasm0(ptr, len) {
        ptr = ptr >>> 0;
        return decodeText(getUint8ArrayMemory0().subarray(ptr, ptr + len));
    }

    let cachedUint8ArrayMemory0 = null;
    function getUint8ArrayMemory0() {
        if (cachedUint8ArrayMemory0 === null || cachedUint8ArrayMemory0.byteLength === 0) {
            cachedUint8ArrayMemory0 = new Uint8Array(wasm.memory.buffer);
        }
        return cachedUint8ArrayMemory0;
    }

    function passStringToWasm0(arg, malloc, realloc) {
        if (realloc === undefined) {
            const buf = cachedTextEncoder.encode(arg);
            const ptr = malloc(buf.length, 1) >>> 0;
            getUint8ArrayMemory0().subarray(ptr, ptr + buf.length).set(buf);
            WASM_VECTOR_LEN = buf.length;
            return ptr;
        }

        let len = arg.length;
        let ptr = malloc(len, 1) >>> 0;

        const mem = getUint8ArrayMemory0();

        let offset = 0;

        for (; offset < len; offset++) {
            const code = arg.charCodeAt(offset);
            if (code > 0x7F) break;
            mem[ptr + offset] = code;
        }
        if (offset !== len) {
            if (offset !== 0) {
                arg = arg.slice(offset);
            }
            ptr = realloc(ptr, len, len = offset + arg.length * 3, 1) >>> 0;
            const view = getUint8ArrayMemory0().subarray(ptr + offset, ptr + len);
            const ret = cachedTextEncoder.encodeInto(arg, view);

            offset += ret.written;
            ptr = realloc(ptr, len, offset, 1) >>> 0;
        }

        WASM_VECTOR_LEN = offset;
        return ptr;
    }

    function takeFromExternrefTable0(idx) {
        const value = wasm.__wbindgen_externrefs.get(idx);
        wasm.__externref_table_dealloc(idx);
        return value;
    }

    let cachedTextDecoder = new TextDecoder('utf-8', { ignoreBOM: true });
    cachedTextDecoder.decode();
    function decodeText(bytes) {
        return cachedTextDecoder.decode(bytes);
    }

    const cachedTextEncoder = new TextEncoder();

    if (!('encodeInto' in cachedTextEncoder)) {
        cachedTextEncoder.encodeInto = function (arg, view) {
            const buf = cachedTextEncoder.encode(arg);
            view.set(buf);
            return {
                read: arg.length,
                written: buf.length
            };
        };
    }

    let WASM_VECTOR_LEN = 0;

    let wasmModule, wasmInstance, wasm;
    function __wbg_finalize_init(instance, module) {
        wasmInstance = instance;
        wasm = instance.exports;
        wasmModule = module;
        cachedUint8ArrayMemory0 = null;
        wasm.__wbindgen_start();
        return wasm;
    }

    async function __wbg_load(module, imports) {
        if (typeof Response === 'function' && module instanceof Response) {
            if (!module.ok) {
                throw new Error(`failed to fetch Wasm: ${module.status} ${module.statusText} fetching '${module.url}'`);
            }

            if (typeof WebAssembly.instantiateStreaming === 'function') {
                try {
                    return await WebAssembly.instantiateStreaming(module, imports);
                } catch (e) {
                    const validResponse = expectedResponseType(module.type);

                    if (validResponse && module.headers.get('Content-Type') !== 'application/wasm') {
                        console.warn("`WebAssembly.instantiateStreaming` failed because your server does not serve Wasm with `application/wasm` MIME type. Falling back to `WebAssembly.instantiate` which is slower. Original error:\n", e);

                    } else { throw e; }
                }
            }

            const bytes = await module.arrayBuffer();
            return await WebAssembly.instantiate(bytes, imports);
        } else {
            const instance = await WebAssembly.instantiate(module, imports);

            if (instance instanceof WebAssembly.Instance) {
                return { instance, module };
            } else {
                return instance;
            }
        }

        function expectedResponseType(type) {
            switch (type) {
                case 'basic': case 'cors': case 'default': return true;
            }
            return false;
        }
    }

    function initSync(module) {
        if (wasm !== undefined) return wasm;


        if (module !== undefined) {
            if (Object.getPrototypeOf(module) === Object.prototype) {
                ({module} = module)
            } else {
                console.warn('using deprecated parameters for `initSync()`; pass a single object instead')
            }
        }

        const imports = __wbg_get_imports();
        if (!(module instanceof WebAssembly.Module)) {
            module = new WebAssembly.Module(module);
        }
        const instance = new WebAssembly.Instance(module, imports);
        return __wbg_finalize_init(instance, module);
    }

    let __wbg_init_promise;
    async function __wbg_init(module_or_path) {
        if (wasm !== undefined) return wasm;
        if (__wbg_init_promise === undefined) {
            __wbg_init_promise = __wbg_init_once(module_or_path);
            __wbg_init_promise.catch(() => { __wbg_init_promise = undefined; });
        }
        return __wbg_init_promise;
    }

    async function __wbg_init_once(module_or_path) {

        if (module_or_path !== undefined) {
            if (Object.getPrototypeOf(module_or_path) === Object.prototype) {
                ({module_or_path} = module_or_path)
            } else {
                console.warn('using deprecated parameters for the initialization function; pass a single object instead')
            }
        }

        if (module_or_path === undefined && script_src !== undefined) {
            module_or_path = script_src.replace(/\.js$/, "_bg.wasm");
        }
        const imports = __wbg_get_imports();

        if (typeof module_or_path === 'string' || (typeof Request === 'function' && module_or_path instanceof Request) || (typeof URL === 'function' && module_or_path instanceof URL)) {
            module_or_path = fetch(module_or_path);
        }

        const { instance, module } = await __wbg_load(await module_or_path, imports);

        return __wbg_finalize_init(instance, module);
    }

    return Object.assign(__wbg_init, { initSync }, exports);
})({ __proto__: null });
