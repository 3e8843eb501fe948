// The export buttons under the stage: the staged figure's genome (JSON, or a GP program as
// an S-expression), its MP4 and strobe PNG, and the run's fitness plot. Each is a POST the
// server answers with a file it keeps in the run's media (the same file the CLI writes).

import { download } from "../api.js";

/**
 * Wire the buttons of #exports.
 * @param {{run: function(): ?object, staged: function(): ?object,
 *   say: function(string, boolean=), attempt: function(function(): Promise)}} page the run
 *   shown, the person on the stage (a pack's individual, or null), and the page's message line
 * @returns {{show: function(object)}} call `show(person)` when the stage changes
 */
export function exportButtons(page) {
  const box = document.getElementById("exports");
  const buttons = [...box.querySelectorAll("button")];
  for (const button of buttons) {
    button.addEventListener("click", () => page.attempt(async () => {
      const run = page.run(), file = button.dataset.file, person = page.staged();
      if (!run || (!person && file !== "plot.png")) throw new Error("no figure on the stage yet");
      const url = file === "plot.png"
        ? `/api/figures/runs/${run.id}/plot.png`
        : `/api/figures/runs/${run.id}/individuals/${person.id}/${file}`;
      page.say(`making ${button.textContent.toLowerCase()}…`);
      for (const b of buttons) b.disabled = true;
      try {
        page.say(`saved ${await download(url)}`);
      } finally {
        for (const b of buttons) b.disabled = false;
        show(page.staged());
      }
    }));
  }
  /** Only a GP program has a text form. */
  function show(person) {
    box.querySelector("[data-file='program.txt']").disabled = !person || !person.program;
  }
  return { show };
}
