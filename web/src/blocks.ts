// Block definitions: one statement block per catalog action (its argument slots are
// object dropdowns of the chosen home) and a free-text block for anything else.
import * as Blockly from "blockly/core";
import type { Action, Category } from "./api";
import { optionsFor } from "./objects";

export const FREE_TEXT = "hs_free_text";
export const TEXT_FIELD = "TEXT";

// Scratch-like palette colours, one per editor category.
export const COLOURS: Record<string, string> = {
  movement: "#4C97FF", attention: "#9966FF", hands: "#CF63CF", placing: "#FFAB19",
  open_close: "#FF8C1A", devices: "#0FBD8C", body: "#5CB1D6", cleaning: "#59C059",
  eating: "#FF6680", free_text: "#8A8A8A",
};

export const blockType = (key: string): string => `hs_${key}`;
export const objectField = (slot: number): string => `OBJ${slot}`;

const actions = new Map<string, Action>(); // by key and by every alias

export function actionOf(type: string): Action | undefined {
  return type.startsWith("hs_") ? actions.get(type.slice(3)) : undefined;
}

/** The catalog action spelled `word` (any case, an alias too), as the server reads it. */
export function lookupAction(word: string): Action | undefined {
  return actions.get(word.toUpperCase().replace(/[\s-]/g, ""));
}

export function defineBlocks(categories: Category[]): void {
  for (const category of categories) {
    for (const action of category.actions) {
      actions.set(action.key, action);
      for (const alias of action.aliases) actions.set(alias, action);
      const colour = COLOURS[category.id] ?? "#888888";
      Blockly.Blocks[blockType(action.key)] = {
        init(this: Blockly.Block) {
          const input = this.appendDummyInput().appendField(action.name);
          for (let slot = 0; slot < action.arity; slot++) {
            if (slot > 0) input.appendField(action.connector ?? "and");
            input.appendField(
              new Blockly.FieldDropdown(() => optionsFor(action, slot)), objectField(slot));
          }
          this.setPreviousStatement(true);
          this.setNextStatement(true);
          this.setColour(colour);
          this.setTooltip(`${action.name}: ${action.description}`);
        },
      };
    }
  }
  Blockly.Blocks[FREE_TEXT] = {
    init(this: Blockly.Block) {
      this.appendDummyInput()
        .appendField("free text")
        .appendField(new Blockly.FieldTextInput("[Action] <object> (1)"), TEXT_FIELD);
      this.setPreviousStatement(true);
      this.setNextStatement(true);
      this.setColour(COLOURS.free_text);
      this.setTooltip("Any step, written as text (for actions the catalog lacks). "
        + "It is sent as it is; the server says if it is not a valid step.");
    },
  };
}

export function toolbox(categories: Category[]): Blockly.utils.toolbox.ToolboxDefinition {
  return {
    kind: "categoryToolbox",
    contents: [
      ...categories.map((c) => ({
        kind: "category",
        name: c.label,
        colour: COLOURS[c.id],
        contents: c.actions.map((a) => ({ kind: "block", type: blockType(a.key) })),
      })),
      {
        kind: "category", name: "Free text", colour: COLOURS.free_text,
        contents: [{ kind: "block", type: FREE_TEXT }],
      },
    ],
  };
}
