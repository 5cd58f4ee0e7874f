#!/usr/bin/env python3
"""Compares a `cinepath mesh` output with the independent OpenDroneMap reference cloud of Brighton Beach
(odm_reference.ply, tests/data/colmap/PROVENANCE.md: EPSG:32615, z WGS84 ellipsoidal; its path in
$ODM_REFERENCE): for each mesh vertex,
the median z of the reference points in its 1 m UTM cell; prints the median vertical difference and the
reference's median ground height under the mesh, the share of vertices more than 1 m off it, how many
more than 3 m, the largest difference, and the share more than 1 m from the median difference. Needs GeographicLib's CartConvert and GeoConvert.
Usage: odm_ground_under_mesh.py OUTDIR [OUTDIR...]   (each holding scene.json and an uncompressed scene.glb)"""
import json,struct,sys,subprocess,collections,statistics
import os
ply=os.environ.get('ODM_REFERENCE')
if not ply:
    sys.exit('set ODM_REFERENCE to the OpenDroneMap reference cloud (odm_reference.ply)')
data=open(ply,'rb').read()
hdr_end=data.index(b'end_header\n')+len('end_header\n')
hdr=data[:hdr_end].decode()
props=[l.split()[1:] for l in hdr.splitlines() if l.startswith('property')]
fmt='<'+''.join({'double':'d','uchar':'B','float':'f','ushort':'H','uint':'I'}[p[0]] for p in props)
cells=collections.defaultdict(list)
for rec in struct.iter_unpack(fmt, data[hdr_end:hdr_end+struct.calcsize(fmt)*int(hdr.split('element vertex ')[1].split()[0])]):
    cells[(int(rec[0]//1),int(rec[1]//1))].append(rec[2])
med={k:statistics.median(v) for k,v in cells.items()}
for d in sys.argv[1:]:
    s=json.load(open(d+'/scene.json')); o=s['origin']
    b=open(d+'/scene.glb','rb').read()
    jl=struct.unpack('<I',b[12:16])[0]; j=json.loads(b[20:20+jl]); bin0=20+jl+8
    acc=j['accessors'][j['meshes'][0]['primitives'][0]['attributes']['POSITION']]; bv=j['bufferViews'][acc['bufferView']]
    off=bin0+bv.get('byteOffset',0)+acc.get('byteOffset',0)
    enu=[struct.unpack_from('<fff',b,off+12*i) for i in range(acc['count'])]
    inp=''.join(f'{x} {-z} {y}\n' for x,y,z in enu)
    geo=subprocess.run(['CartConvert','-r','-l',str(o['lat_deg']),str(o['lon_deg']),str(o['height_m']),'-p','9'],input=inp,capture_output=True,text=True).stdout.split('\n')
    geo=[l.split() for l in geo if l.strip()]
    utm=subprocess.run(['GeoConvert','-u','-p','3','-z','15'],input=''.join(f'{g[0]} {g[1]}\n' for g in geo),capture_output=True,text=True).stdout.split('\n')
    utm=[l.split() for l in utm if l.strip()]
    diffs=[]; refs=[]
    for g,u in zip(geo,utm):
        k=(int(float(u[1])//1),int(float(u[2])//1))
        if k in med: diffs.append(float(g[2])-med[k]); refs.append(med[k])
    diffs.sort()
    print(d,'n',len(diffs),'of',len(geo),'median mesh-ODM vertical',round(statistics.median(diffs),2),'p10',round(diffs[len(diffs)//10],2),'p90',round(diffs[9*len(diffs)//10],2),'ODM median ground there',round(statistics.median(refs),2),
          'over 1 m',f'{100*sum(abs(x)>1 for x in diffs)/len(diffs):.2f}%','over 3 m',sum(abs(x)>3 for x in diffs),
          'max',round(max(abs(x) for x in diffs),2),
          'over 1 m from the median',f'{100*sum(abs(x-statistics.median(diffs))>1 for x in diffs)/len(diffs):.2f}%')
