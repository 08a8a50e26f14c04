// Vite's asset imports, for the type check of web/src (tsconfig.json).
declare module '*?url' {
  const url: string;
  export default url;
}
declare module '*?worker&url' {
  const url: string;
  export default url;
}
