// Drag-and-drop of one or more files anywhere on the page.
export function installDrop(target, onFiles) {
  const hint = document.getElementById('drop-hint');
  let depth = 0;
  target.addEventListener('dragenter', (event) => {
    event.preventDefault();
    depth += 1;
    hint.hidden = false;
  });
  target.addEventListener('dragleave', () => {
    depth = Math.max(0, depth - 1);
    if (!depth) hint.hidden = true;
  });
  target.addEventListener('dragover', (event) => event.preventDefault());
  target.addEventListener('drop', (event) => {
    event.preventDefault();
    depth = 0;
    hint.hidden = true;
    onFiles([...(event.dataTransfer?.files ?? [])]);
  });
}
