// The WebAssembly module's files for a list of jobs, run in Node's V8 (the browser's engine):
//   node tests/wasm_files.js MODULE_DIR JOBS.json
// MODULE_DIR holds what web/build.sh makes (mechdraw.js, the wasm-bindgen glue, and
// mechdraw_bg.wasm). JOBS.json is a list of {"text", "file", "out", "frames"}: each job's scene
// text is run through the module's run_scene (the command line's `mechdraw run`, with
// --no-frames unless frames) and every file it returns is written under its "out" directory.
// Used by tests/wasm_bytes.rs, which compares them with the native build's bytes.
const fs = require("fs"), vm = require("vm"), path = require("path");
const [dir, jobsFile] = process.argv.slice(2);
globalThis.self = globalThis;
vm.runInThisContext(fs.readFileSync(path.join(dir, "mechdraw.js"), "utf8"));
(async () => {
  await wasm_bindgen({ module_or_path: fs.readFileSync(path.join(dir, "mechdraw_bg.wasm")) });
  for (const job of JSON.parse(fs.readFileSync(jobsFile, "utf8"))) {
    let files;
    try {
      files = wasm_bindgen.run_scene(job.text, job.file, job.frames);
    } catch (e) {
      console.error(`${job.file}: ${e}`);
      process.exit(1);
    }
    const names = [];
    for (let i = 0; i < files.count(); i++) {
      const name = files.name(i);
      const p = path.join(job.out, name);
      fs.mkdirSync(path.dirname(p), { recursive: true });
      fs.writeFileSync(p, files.bytes(i));
      names.push(name);
    }
    // The module's order, for the test to compare with the native one.
    fs.writeFileSync(path.join(job.out, ".names.json"), JSON.stringify(names));
    console.log(`${job.file}: ${names.length} files`);
    files.free();
  }
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
