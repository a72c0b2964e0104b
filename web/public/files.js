// Files the server answers inside JSON ({name, media_type, text or base64}: the nav2 mask, its
// YAML, the waypoints YAML...), offered as download links made here (blob: URLs).

/// A Blob of one answered file.
export function fileBlob(file) {
  if (typeof file.text === 'string') return new Blob([file.text], { type: file.media_type });
  const bytes = Uint8Array.from(atob(file.base64), (c) => c.charCodeAt(0));
  return new Blob([bytes], { type: file.media_type });
}

/// Fills `container` with one download link per file (the links made before are let go).
export function showDownloads(container, files) {
  for (const link of container.querySelectorAll('a[href^="blob:"]')) URL.revokeObjectURL(link.href);
  container.replaceChildren(...files.map((file) => {
    const link = document.createElement('a');
    link.href = URL.createObjectURL(fileBlob(file));
    link.download = file.name;
    link.textContent = file.name;
    link.className = 'fg-download';
    link.title = `${file.media_type}: save it`;
    return link;
  }));
}
