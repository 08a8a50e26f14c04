// Modules without types of their own, for the type check of web/src (tsconfig.json): Vite's asset imports, npm draco3d's decoder.
declare module '*?url' {
  const url: string;
  export default url;
}
declare module '*?worker&url' {
  const url: string;
  export default url;
}
// npm draco3d's decoder glue (CommonJS, no types): the worker calls only its factory.
declare module 'draco3d/draco_decoder_nodejs.js' {
  const createDecoderModule: (settings?: { locateFile?: (file: string) => string }) => Promise<any>;
  export default createDecoderModule;
}
