// Builds the editor into the Python package (src/homesim/serve/static), which
// `homesim serve` serves. Blockly's media (sprites, cursors, sounds) is copied next to it
// so the page needs nothing from the internet.
import { cpSync } from "node:fs";
import { fileURLToPath } from "node:url";
import { defineConfig, type Plugin } from "vite";

const outDir = fileURLToPath(new URL("../src/homesim/serve/static", import.meta.url));
const blocklyMedia = fileURLToPath(new URL("./node_modules/blockly/media", import.meta.url));

function copyBlocklyMedia(): Plugin {
  return {
    name: "copy-blockly-media",
    apply: "build",
    closeBundle() {
      cpSync(blocklyMedia, `${outDir}/media`, { recursive: true });
    },
  };
}

export default defineConfig({
  base: "./",
  build: { outDir, emptyOutDir: true, chunkSizeWarningLimit: 2000 },
  plugins: [copyBlocklyMedia()],
  server: { proxy: { "/api": "http://127.0.0.1:8000" } },
});
