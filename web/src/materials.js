// Materials by render quality: physically based when a GPU is there, Lambert on
// software GL (several times cheaper per pixel, so the page keeps up with the stream).
import * as THREE from 'three';

export const quality = { low: false };

export function material({ roughness, metalness, ...params }) {
  return quality.low ? new THREE.MeshLambertMaterial(params) : new THREE.MeshStandardMaterial({ roughness, metalness, ...params });
}
