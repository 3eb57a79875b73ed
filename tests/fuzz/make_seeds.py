#!/usr/bin/env python3
# Writes the fuzz targets' seed corpus (tests/fuzz/corpus/TARGET/): small valid and near-valid files
# shaped as the tests' fixtures and the project's writers make them (a few KB each; the shipped
# measurements and tissue model cut down or compacted), and each target's dictionary
# (tests/fuzz/dict/TARGET.dict). Run by hand; what it writes is committed.
#   python3 tests/fuzz/make_seeds.py
import os, zlib, gzip, json, struct, io
here=os.path.dirname(os.path.abspath(__file__)); repo=os.path.dirname(os.path.dirname(here))
root=os.path.join(here,'corpus')
def put(t, name, data):
    d=os.path.join(root,t); os.makedirs(d,exist_ok=True)
    if isinstance(data,str): data=data.encode()
    open(os.path.join(d,name),'wb').write(data)
def gz(b): 
    out=io.BytesIO()
    with gzip.GzipFile(fileobj=out,mode='wb',mtime=0) as f: f.write(b)
    return out.getvalue()
# --- measurements
lines=open(os.path.join(repo,'assets/measurements/thigh.csv')).read().splitlines()
head=[l for l in lines if l.startswith('#')][:2]
hdr='point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm,force_N'
rows=[l for l in lines if l and l[0].isdigit()]
ind=[r for r in rows if ',indenter,' in r][:6]; prb=[r for r in rows if ',probe,' in r][:6]
put('measurements','thigh_head.csv','\n'.join(head+[hdr]+ind+prb)+'\n')
put('measurements','reordered_crlf.csv','force_N,depth_mm,probe,point,x_mm,y_mm,z_mm,nx,ny,nz\r\n0.5,2,probe,3,1,2,3,0,0,1\r\n1.25,4,indenter,3,1,2,3,0,0.6,0.8\r\n')
put('measurements','bad_normal.csv',hdr+'\n0,indenter,1,2,3,0,0,2,2,0.3\n')
# --- tissue model: the shipped one, compact
m=json.load(open(os.path.join(repo,'assets/models/thigh.json')))
def rnd(x):
    if isinstance(x,float): return float('%.6g'%x)
    if isinstance(x,list): return [rnd(v) for v in x]
    if isinstance(x,dict): return {k:rnd(v) for k,v in x.items()}
    return x
m=rnd(m)
# renormalise normals after rounding
import math
ns=m['nodes']['normal']
m['nodes']['normal']=[[float('%.6g'%(c/math.sqrt(sum(v*v for v in n)))) for c in n] for n in ns]
put('tissue_model','thigh.json',json.dumps(m,separators=(',',':')))
m2=dict(m); m2['version']=2
put('tissue_model','version2.json',json.dumps(m2,separators=(',',':')))
put('tissue_model','grid_only.json','{"format":"echosim-tissue-model","version":1,"grid":{"rows":8,"cols":8,"refine":1},"lambda_N_per_mm":1,"mu_Ns_per_mm":0.1,"fit":{"method":"lm","samples":3}}')
# --- trajectory
put('trajectory','two_rows.csv','t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n0,0,0,0,1,0,0,0\n0.5,10,-2.5,3,0.70710678118654757,0,0.70710678118654757,0\n')
put('trajectory','crlf_three.csv','t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\r\n0,1e-3,2,3,1,0,0,0\r\n1,4,5,6,0,1,0,0\r\n2.5,-7,8,9,0.5,0.5,0.5,0.5\r\n')
put('trajectory','not_increasing.csv','t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n1,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n')
# --- plus config: the test's configuration and a few variants
cfg=open(os.path.join(repo,'tests/io/plus_config_test.cpp')).read()
a=cfg.index('R"(')+3; b=cfg.index(')"',a)
conf=cfg[a:b]
put('plus_config','device_set.xml',conf)
put('plus_config','minimal.xml','<PlusConfiguration version="2.3"><CoordinateDefinitions><Transform From="Image" To="Probe" Matrix="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/></CoordinateDefinitions><VolumeReconstruction OutputSpacing="1 1 1" OutputOrigin="0 0 0" OutputExtent="0 9 0 9 0 9" Compounding="On" Calculation="WEIGHTED_AVERAGE" FillHoles="ON" PixelRejectionThreshold="5"/></PlusConfiguration>')
put('plus_config','wrong_root.xml','<?xml version="1.0"?><Configuration/>')
# --- volumes: NRRD as write_nrrd writes it, raw and gzip; Slicer-style RAS
vox=bytes(range(24))
def nrrd(enc, data, typ='unsigned char', extra=''):
    h=('NRRD0004\n# Complete NRRD file format specification at:\n# http://teem.sourceforge.net/nrrd/format.html\n'
       'type: %s\ndimension: 3\nspace: left-posterior-superior\nsizes: 4 3 2\n'
       'space directions: (0.5,0,0) (0,0.25,0) (0,0,2)\nkinds: domain domain domain\nendian: little\n'
       'encoding: %s\nspace origin: (-10,20,5)\n%slabel_1:=skin\n\n')%(typ,enc,extra)
    return h.encode()+data
put('nrrd','raw.nrrd',nrrd('raw',vox))
put('nrrd','gzip.nrrd',nrrd('gzip',gz(vox)))
put('nrrd','ushort_ras.nrrd',nrrd('raw',vox*2,'unsigned short').replace(b'left-posterior-superior',b'right-anterior-superior'))
put('nrrd','float_spacings.nrrd',b'NRRD0005\ntype: float\ndimension: 3\nsizes: 2 2 1\nspacings: 1 1 1\nendian: little\nencoding: gz\n\n'+gz(struct.pack('<4f',0,1.5,-2,1e30)))
# MetaImage as ITK writes it (metaimage_test's header), raw and compressed, and detached
itk=('ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\nCompressedData = False\n'
     'TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = -10 20 5\nCenterOfRotation = 0 0 0\nAnatomicalOrientation = ALI\n'
     'ElementSpacing = 0.5 0.25 2\nDimSize = 4 3 2\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n')
z=zlib.compress(vox)
itkz=itk.replace('CompressedData = False','CompressedData = True\nCompressedDataSize = %d'%len(z))
put('metaimage','itk_raw.mha',itk.encode()+vox)
put('metaimage','itk_zlib.mha',itkz.encode()+z)
put('metaimage','short_msb.mha',itk.replace('MET_UCHAR','MET_SHORT').replace('ByteOrderMSB = False','ByteOrderMSB = True').encode()+vox*2)
put('metaimage','detached_self.mha',itk.replace('ElementDataFile = LOCAL','ElementDataFile = volume.mha').encode())
put('metaimage','double_2d.mha','ObjectType = Image\r\nNDims = 2\r\nDimSize = 2 2\r\nElementSize = 1 1\r\nElementType = MET_DOUBLE\r\nElementDataFile = LOCAL\r\n'.encode()+struct.pack('<4d',0,1,2,3))
for n in ['raw.nrrd','gzip.nrrd']: put('volume',n,open(os.path.join(root,'nrrd',n),'rb').read())
for n in ['itk_raw.mha','itk_zlib.mha']: put('volume',n,open(os.path.join(root,'metaimage',n),'rb').read())
# --- PLUS sequences: as write_plus_mha writes them, and as PLUS does (ProbeToTracker + ImageToProbe)
def plus_mha(w,h,n,compressed):
    px=bytes((i*7)%256 for i in range(w*h*n))
    packed=zlib.compress(px)
    s='ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\nBinaryDataByteOrderMSB = False\nCenterOfRotation = 0 0 0\n'
    s+='CompressedData = %s\n'%('True' if compressed else 'False')
    if compressed: s+='CompressedDataSize = %d\n'%len(packed)
    s+='DimSize = %d %d %d\nElementNumberOfChannels = 1\nElementSpacing = 1 1 1\nKinds = domain domain list\nOffset = 0 0 0\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n'%(w,h,n)
    s+='UltrasoundImageOrientation = MF\nUltrasoundImageType = BRIGHTNESS\n'
    for i in range(n):
        s+='Seq_Frame%04d_ImageToReferenceTransform = 0.2 0 0 %g 0 0.2 0 6 0 0 0.2 7 0 0 0 1\n'%(i,5+i)
        s+='Seq_Frame%04d_ImageToReferenceTransformStatus = %s\n'%(i,'OK' if i!=1 else 'INVALID')
        s+='Seq_Frame%04d_Timestamp = %g\n'%(i,12.5+0.5*i)
    s+='ElementType = MET_UCHAR\nElementDataFile = LOCAL\n'
    return s.encode()+(packed if compressed else px)
put('plus_mha','raw.igs.mha',plus_mha(7,5,3,False))
put('plus_mha','zlib.igs.mha',plus_mha(7,5,3,True))
t=open(os.path.join(repo,'tests/io/plus_sequence_test.cpp')).read()
probe=('ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\nBinaryDataByteOrderMSB = False\nCenterOfRotation = 0 0 0\nCompressedData = False\nDimSize = 3 2 2\n'
 'ElementNumberOfChannels = 1\nElementSpacing = 1 1 1\nKinds = domain domain list\nOffset = 0 0 0\nTransformMatrix = 1 0 0 0 1 0 0 0 1\nUltrasoundImageOrientation = UN\nUltrasoundImageType = BRIGHTNESS\n'
 'ImageToProbeTransform = 0.1 0 0 -0.15 0 0.1 0 0 0 0 0.1 0 0 0 0 1\n'
 'Seq_Frame0000_ProbeToTrackerTransform = 0 -1 0 10 1 0 0 20 0 0 1 30 0 0 0 1\nSeq_Frame0000_ProbeToTrackerTransformStatus = OK\nSeq_Frame0000_Timestamp = 1.25\nSeq_Frame0000_ImageStatus = OK\n'
 'Seq_Frame0001_ProbeToTrackerTransform = 1 0 0 -5 0 0 -1 2.5 0 1 0 7 0 0 0 1\nSeq_Frame0001_ProbeToTrackerTransformStatus = MISSING\nSeq_Frame0001_Timestamp = 1.3\nSeq_Frame0001_ImageStatus = OK\n'
 'Seq_Frame0001_ReferenceToTrackerTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\nSeq_Frame0001_ReferenceToTrackerTransformStatus = OK\n'
 'ElementType = MET_UCHAR\nElementDataFile = LOCAL\n')
put('plus_mha','probe_to_tracker.mha',probe.encode()+b'abcdefghijkl')
put('plus_mha','crlf_ushort.mha',(probe.replace('MET_UCHAR','MET_USHORT').replace('\n','\r\n')).encode()+b'abcdefghijklabcdefghijkl')
seq=('NRRD0004\n# Complete NRRD file format specification at:\n# http://teem.sourceforge.net/nrrd/format.html\n'
 'dimension: 3\nencoding: %s\nendian: little\nkinds: domain domain list\nsizes: 3 2 2\n'
 'space dimension: 2\nspace directions: (1,0) (0,1) none\nspace origin: (0,0)\ntype: unsigned char\n'
 'ultrasound image orientation:=MF\nultrasound image type:=BRIGHTNESS\n'
 'Seq_Frame0000_ImageToReferenceTransform:=0.2 0 0 5 0 0.2 0 6 0 0 0.2 7 0 0 0 1\n'
 'Seq_Frame0000_ImageToReferenceTransformStatus:=OK\nSeq_Frame0000_Timestamp:=100.5\n'
 'Seq_Frame0001_ImageToReferenceTransform:=0.2 0 0 5 0 0.2 0 6 0 0 0.2 9 0 0 0 1\n'
 'Seq_Frame0001_ImageToReferenceTransformStatus:=INVALID\nSeq_Frame0001_Timestamp:=100.55\n\n')
pix=b'ABCDEFabcdef'
put('plus_seq_nrrd','raw.seq.nrrd',(seq%'raw').encode()+pix)
put('plus_seq_nrrd','gz.seq.nrrd',(seq%'gz').encode()+gz(pix))
put('plus_seq_nrrd','list_first.seq.nrrd',(seq%'raw').replace('kinds: domain domain list','kinds: list domain domain').replace('sizes: 3 2 2','sizes: 2 3 2').encode()+pix)
put('plus_seq_nrrd','four_d.seq.nrrd',(seq%'raw').replace('sizes: 3 2 2','sizes: 3 2 1 2').replace('dimension: 3','dimension: 4').replace('kinds: domain domain list','kinds: domain domain domain list').encode()+pix)
for n in ['raw.igs.mha','zlib.igs.mha','probe_to_tracker.mha']: put('plus_sequence',n,open(os.path.join(root,'plus_mha',n),'rb').read())
for n in ['raw.seq.nrrd','gz.seq.nrrd']: put('plus_sequence',n,open(os.path.join(root,'plus_seq_nrrd',n),'rb').read())

# --- dictionaries (tests/fuzz/dict/TARGET.dict): the formats' keywords and the numbers that matter
# (sizes past 32 and 64 bits, past the budgets, non-finite values, devices as data files), so that
# libFuzzer's mutations reach past the header's spelling in seconds rather than hours
numbers=['0','-1','1e999','-1e999','nan','inf','65536','4294967295','4294967296','2147483648','18446744073709551615',
         '18446744073709551616','1e308','0.5','3 2 2','2048 2048 1024','65536 65536 65536']
devices=['/dev/zero','/dev/stdin','/dev/null','.','..','/']
nrrd_words=['NRRD0001','NRRD0004','NRRD0005','type: ','dimension: ','sizes: ','space: ','space directions: ','space origin: ',
  'space dimension: ','space units: ','spacings: ','kinds: ','endian: ','encoding: ','data file: ','datafile: ','line skip: ',
  'byte skip: ',':=','gzip','gz','raw','little','big','domain','space','list','none','???','unsigned char','unsigned short',
  'short','float','double','left-posterior-superior','right-anterior-superior','left-anterior-superior','RAS','(1,0,0)','(0,0)',
  '"mm"','\x1f\x8b\x08\x00','\n\n']
meta_words=['ObjectType = Image','NDims = ','DimSize = ','ElementType = ','MET_UCHAR','MET_CHAR','MET_USHORT','MET_SHORT',
  'MET_FLOAT','MET_DOUBLE','MET_INT','ElementDataFile = ','LOCAL','LIST','%03d','CompressedData = True','CompressedDataSize = ',
  'BinaryData = False','BinaryDataByteOrderMSB = True','ElementByteOrderMSB = True','ElementNumberOfChannels = ',
  'ElementSpacing = ','ElementSize = ','TransformMatrix = ','Offset = ','Position = ','Origin = ','AnatomicalOrientation = ',
  'HeaderSize = ',' = ','\r\n','x\x9c','x\x01']
plus_words=['Seq_Frame0000_','Seq_Frame0001_','Seq_Frame0002_','ImageToReferenceTransform','ProbeToTrackerTransform',
  'ImageToProbeTransform','ReferenceToTrackerTransform','ImageToTrackerTransform','TransformStatus','Transform = ','OK',
  'INVALID','MISSING','Timestamp = ','ImageStatus = ','Status:=','UltrasoundImageOrientation = ','ultrasound image orientation:=',
  'MF','UF','MN','UN','MFA','AMF','Kinds = domain domain list','1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1']
xml_words=['<?xml version="1.0"?>','<PlusConfiguration version="2.1">','</PlusConfiguration>','<CoordinateDefinitions>',
  '</CoordinateDefinitions>','<Transform ','From="','To="','Matrix="','Valid="','<VolumeReconstruction ','/>','<!--','-->',
  '<![CDATA[',']]>','&amp;','&#x41;','&#65;']+['%s="'%a for a in ['OutputSpacing','OutputOrigin','OutputExtent',
  'ClipRectangleOrigin','ClipRectangleSize','Interpolation','CompoundingMode','Compounding','Calculation','FillHoles',
  'HoleFilling','PixelRejectionThreshold','ReferenceCoordinateFrame','ImageCoordinateFrame','FanAnglesDeg','FanOrigin',
  'FanDepth','Optimization','NumberOfThreads','SkipInterval','ImportanceMaskFilename','EnableFanAnglesAutoDetect']]+['LINEAR',
  'NEAREST_NEIGHBOR','MEAN','MAXIMUM','LATEST','ON','OFF','TRUE','FALSE','FULL']
json_words=['"%s":'%k for k in ['format','version','grid','rows','cols','refine','lambda_N_per_mm','mu_Ns_per_mm','samples',
  'a_per_N','b_mm_per_N','fit','method','seconds','mae_N','sd_N','rel_error','nodes','position_mm','normal','mass_kg',
  'boundary','springs_i_j_rest_mm','provenance']]+['"echosim-tissue-model"','null','true','[]','{}','[[[[[[[[',
  '\\u0000','\\ud800']
csv_words=['point','probe','x_mm','y_mm','z_mm','nx','ny','nz','depth_mm','force_N','indenter',',','#','\r\n']
trajectory_words=['t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz','0.70710678118654757',',','\r\n']
def put_dict(target, words):
    d=os.path.join(here,'dict'); os.makedirs(d,exist_ok=True)
    def quote(w):
        return '"'+''.join(c if 32<=ord(c)<127 and c not in '"\\' else '\\x%02x'%ord(c) for c in w)+'"'
    open(os.path.join(d,target+'.dict'),'w').write(''.join(quote(w)+'\n' for w in words+numbers))
put_dict('measurements', csv_words)
put_dict('trajectory', trajectory_words)
put_dict('tissue_model', json_words)
put_dict('plus_config', xml_words)
put_dict('nrrd', nrrd_words)
put_dict('metaimage', meta_words+devices)
put_dict('volume', nrrd_words+meta_words+devices)
put_dict('plus_mha', meta_words+plus_words+devices)
put_dict('plus_seq_nrrd', nrrd_words+plus_words)
put_dict('plus_sequence', nrrd_words+meta_words+plus_words+devices)
