// An error the user caused (bad file, unsupported format): its message is
// the one sentence the page shows.
export class MeshError extends Error {
  constructor(message, kind = 'InvalidInput') {
    super(message);
    this.name = 'MeshError';
    this.kind = kind;
  }
}
