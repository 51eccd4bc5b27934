// MaterialX's own document validation, with its standard libraries loaded, on each .mtlx given:
//   node mtlx_validate.cjs NPM_DIR FILE...
// prints one JSON line per file: {file, valid, message, version, images: [{name, type, file,
// colorspace}], shaders: [{category, inputs: {name: nodename or value}}], extracts: {name: index}}.
// MaterialX 1.39 comes from npm (@needle-tools/materialx: its JsMaterialXGenShader WebAssembly
// build, scripts/npm-checkers.sh); Node loads it after two shims: the module
// without its final ES `export`, as CommonJS, and the data file under the name it asks for.
// readFromXmlString is asynchronous in this build: awaited, or the document stays empty. The
// standard libraries are the document's data library: validate() checks every node against
// their nodedefs as with a copy (Gltf.MaterialXCheckerRefusesBrokenDocuments).
const fs = require('fs'), path = require('path'), os = require('os');
const bin = path.join(process.argv[2], 'node_modules/@needle-tools/materialx/bin');
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'matforge-mtlx-'));
const js = fs.readFileSync(path.join(bin, 'JsMaterialXGenShader.js'), 'utf8').replace(/\nexport default MaterialX;\s*$/, '\n');
fs.writeFileSync(path.join(work, 'JsMaterialXGenShader.cjs'), js);
fs.copyFileSync(path.join(bin, 'JsMaterialXGenShader.wasm'), path.join(work, 'JsMaterialXGenShader.wasm'));
fs.copyFileSync(path.join(bin, 'JsMaterialXGenShader.data.txt'), path.join(work, 'JsMaterialXGenShader.data'));
const factory = require(path.join(work, 'JsMaterialXGenShader.cjs'));
factory({locateFile: (p) => path.join(work, p)}).then(async (mx) => {
  const stdlib = mx.loadStandardLibraries(new mx.GenContext(mx.EsslShaderGenerator.create()));
  for (const file of process.argv.slice(3)) {
    const out = {file, version: mx.getVersionString()};
    try {
      const doc = mx.createDocument();
      await mx.readFromXmlString(doc, fs.readFileSync(file, 'utf8'));
      doc.setDataLibrary(stdlib);  // referenced, not copied (importLibrary took 2 s a document)
      const msg = {};
      out.valid = doc.validate(msg);
      out.message = msg.message || '';
      out.images = [];
      out.shaders = [];
      out.extracts = {};
      for (const node of doc.getNodes()) {
        const category = node.getCategory();
        if (category === 'image') {
          const f = node.getInput('file');
          out.images.push({name: node.getName(), type: node.getType(), file: f.getValueString(),
                           colorspace: f.getColorSpace()});
        } else if (category === 'extract') {
          out.extracts[node.getName()] = node.getInput('index').getValueString();
        } else if (node.getType() === 'surfaceshader') {
          const inputs = {};
          for (const i of node.getInputs()) inputs[i.getName()] = i.getNodeName() || i.getValueString();
          out.shaders.push({category, inputs, nodedef: !!node.getNodeDef()});
        }
      }
    } catch (e) {
      out.valid = false;
      out.message = String((e && e.message) || e);
    }
    console.log(JSON.stringify(out));
  }
  fs.rmSync(work, {recursive: true, force: true});
});
